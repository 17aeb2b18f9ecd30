// What the tests of the volumetric models (pressure_field_test.cc, inner_spheres_test.cc)
// share: a sampled ball, random overlapping poses, a query, and K_B by central differences of
// the wrench in B's pose (contact_model.h's convention), the independent check of each model's
// own K_B.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <vector>

#include "contact/contact_model.h"
#include "contact/test_shells.h"
#include "geometry/pose.h"

namespace contactlab::testing {

// A ball of radius R at the origin sampled with spacing H, a grid node at its centre and
// MARGIN_CELLS cells or more around it.
inline std::shared_ptr<DistanceField> BallField(double R, double h, int margin_cells) {
  const double m = std::ceil((R + margin_cells * h) / h) * h;
  return SampleField([R](const Eigen::Vector3d& p) { return p.norm() - R; }, Eigen::Vector3d::Constant(-m),
                     Eigen::Vector3d::Constant(m), h);
}

inline ContactQuery At(const Pose& X_WA, const Pose& X_WB, std::int64_t node_budget = 0) {
  ContactQuery q;
  q.X_WA = X_WA;
  q.X_WB = X_WB;
  q.node_budget = node_budget;
  return q;
}

inline Pose Translation(double x, double y, double z) { return Pose::FromTranslation(Eigen::Vector3d(x, y, z)); }

// N random pose pairs from SEED: A turned anyhow within a centimetre of the origin, B turned
// anyhow with its origin DISTANCE from A's in a random direction.
struct Overlap {
  Pose X_WA, X_WB;
};
inline std::vector<Overlap> RandomOverlaps(int n, double distance, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<Overlap> out;
  for (int i = 0; i < n; ++i) {
    Overlap o;
    o.X_WA = Pose{Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized(),
                  Eigen::Vector3d(g(rng), g(rng), g(rng)) * 0.01};
    const Eigen::Vector3d dir(g(rng), g(rng), g(rng));
    o.X_WB = Pose{Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized(),
                  o.X_WA.translation + distance * dir.normalized()};
    out.push_back(o);
  }
  return out;
}

// d(WRENCH)/d(pose of B) at X_WB by central differences: steps DX (m) along the world axes and
// DW (rad) about them, B's rotation turned as exp([dθ]) R_WB.
inline Matrix6d CentralDifferenceStiffness(const std::function<Vector6d(const Pose& X_WB)>& wrench, const Pose& X_WB,
                                           double dx, double dw) {
  Matrix6d K;
  for (int c = 0; c < 6; ++c) {
    Vector6d w[2];
    for (int s = 0; s < 2; ++s) {
      Pose X = X_WB;
      const double sign = s == 0 ? 1 : -1;
      if (c < 3) {
        X.translation[c] += sign * dx;
      } else {
        Eigen::Vector3d v = Eigen::Vector3d::Zero();
        v[c - 3] = sign * dw;
        X.rotation = (RotationFromVector(v) * X.rotation).normalized();
      }
      w[s] = wrench(X);
    }
    K.col(c) = (w[0] - w[1]) / (2 * (c < 3 ? dx : dw));
  }
  return K;
}

}  // namespace contactlab::testing
