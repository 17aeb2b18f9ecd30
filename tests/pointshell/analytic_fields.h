// Distance fields sampled from analytic functions, for the pointshell tests.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "sdf/distance_field.h"

namespace contactlab::testing {

// Samples F on an N^3 grid covering [-L, L]^3.
inline DistanceField SampledField(const std::function<double(const Eigen::Vector3d&)>& f, double half_extent, int n,
                                  const std::string& name) {
  const double h = 2 * half_extent / (n - 1);
  const Eigen::Vector3d origin = Eigen::Vector3d::Constant(-half_extent);
  std::vector<float> v;
  v.reserve(std::size_t(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(float(f(origin + h * Eigen::Vector3d(i, j, k))));
  return DistanceField(origin, h, Eigen::Vector3i::Constant(n), std::move(v), {name, "analytic", 0, 0});
}

// Exact signed distance of a sphere of RADIUS centred at the origin.
inline DistanceField SampledSphere(double radius, double half_extent, int n) {
  return SampledField([radius](const Eigen::Vector3d& p) { return p.norm() - radius; }, half_extent, n, "sphere");
}

}  // namespace contactlab::testing
