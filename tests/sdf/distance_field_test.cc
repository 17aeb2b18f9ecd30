#include "sdf/distance_field.h"

#include <gtest/gtest.h>

#include <random>

#include "util/error.h"

namespace contactlab {
namespace {

// Samples the sphere's exact signed distance on a grid covering [-L, L]^3.
DistanceField SampledSphere(double radius, double half_extent, int n) {
  const double h = 2 * half_extent / (n - 1);
  const Eigen::Vector3d origin = Eigen::Vector3d::Constant(-half_extent);
  std::vector<float> v;
  v.reserve(std::size_t(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(float((origin + h * Eigen::Vector3d(i, j, k)).norm() - radius));
  return DistanceField(origin, h, Eigen::Vector3i::Constant(n), std::move(v), {"sphere", "analytic", 0, 0});
}

TEST(DistanceField, TrilinearErrorWithinBoundForGridSpacing) {
  const double R = 0.3;
  const DistanceField f = SampledSphere(R, 0.5, 65);
  const double h = f.spacing();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.49, 0.49);
  for (int s = 0; s < 2000; ++s) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (p.norm() < 2 * h) continue;  // the cone tip at the centre is not smooth
    // Trilinear error <= (h^2/8) * max|second derivative| summed over axes, |d''| <= 1/|p|.
    const double bound = 3 * h * h / 8 / (p.norm() - std::sqrt(3.0) * h) + 1e-6;
    EXPECT_NEAR(f.Distance(p), p.norm() - R, bound) << p.transpose();
  }
}

TEST(DistanceField, GradientMatchesFiniteDifferencesOfTheInterpolant) {
  const DistanceField f = SampledSphere(0.3, 0.5, 33);
  const Eigen::Vector3d p(0.1234, -0.2111, 0.0777);
  Eigen::Vector3d g;
  f.DistanceAndGradient(p, &g);
  const double e = 1e-6;
  for (int a = 0; a < 3; ++a) {
    Eigen::Vector3d dp = Eigen::Vector3d::Zero();
    dp[a] = e;
    const double fd = (f.DistanceAndGradient(p + dp, nullptr) - f.DistanceAndGradient(p - dp, nullptr)) / (2 * e);
    EXPECT_NEAR(g[a], fd, 1e-6);
  }
  EXPECT_NEAR(g.norm(), 1.0, 0.05);
}

TEST(DistanceField, OutsideBoxBoundNeverOverestimates) {
  const DistanceField f = SampledSphere(0.3, 0.5, 33);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3, 3);
  int outside = 0;
  for (int s = 0; s < 5000; ++s) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (f.Inside(p)) continue;
    ++outside;
    EXPECT_LE(f.Distance(p), p.norm() - 0.3 + 1e-5) << p.transpose();
  }
  EXPECT_GT(outside, 1000);
}

TEST(DistanceField, FloatAndDoubleQueriesAgree) {
  const DistanceField f = SampledSphere(0.3, 0.5, 33);
  const Eigen::Vector3d p(0.31, 0.02, -0.4);
  EXPECT_NEAR(f.Distance(p), f.DistanceAndGradient(p, nullptr), 1e-6);
  EXPECT_EQ(f.Distance(Eigen::Vector3d(0.5, 0.5, 0.5)), f.value(32, 32, 32));
}

TEST(DistanceField, InconsistentSizesAreRejected) {
  EXPECT_THROW(DistanceField(Eigen::Vector3d::Zero(), 0.1, Eigen::Vector3i(2, 2, 2), std::vector<float>(7)), Error);
  EXPECT_THROW(DistanceField(Eigen::Vector3d::Zero(), -0.1, Eigen::Vector3i(2, 2, 2), std::vector<float>(8)), Error);
  std::vector<float> v(8, 0.f);
  v[3] = std::nanf("");
  EXPECT_THROW(DistanceField(Eigen::Vector3d::Zero(), 0.1, Eigen::Vector3i(2, 2, 2), v), Error);
}

}  // namespace
}  // namespace contactlab
