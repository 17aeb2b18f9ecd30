// The vectorised lookups on every instruction set this CPU runs, against the closed form of a
// field trilinear interpolation reproduces exactly (an affine function) and against the
// scalar lookup.
#include "sdf/batch_distance.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace contactlab {
namespace {

// f(p) = a . p + b sampled on a 17 x 23 x 29 grid (unequal sizes catch stride mistakes).
struct AffineField {
  Eigen::Vector3d a{0.3, -0.7, 0.5};
  double b = -0.01;
  Eigen::Vector3d origin{-0.05, -0.02, 0.01};
  double h = 0.004;
  Eigen::Vector3i dims{17, 23, 29};
  DistanceField field;
  AffineField() {
    std::vector<float> v;
    for (int k = 0; k < dims.z(); ++k)
      for (int j = 0; j < dims.y(); ++j)
        for (int i = 0; i < dims.x(); ++i) v.push_back(float(a.dot(origin + h * Eigen::Vector3d(i, j, k)) + b));
    field = DistanceField(origin, h, dims, std::move(v));
  }
  Eigen::Vector3d upper() const { return origin + h * (dims - Eigen::Vector3i::Ones()).cast<double>(); }
  // The exact value inside the box, the Fig. 5(c) bound outside it.
  double Exact(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d lo = origin, hi = upper();
    const Eigen::Vector3d out = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
    if (out.squaredNorm() == 0) return a.dot(p) + b;
    // The affine function's minimum over the boundary is at the box corner minimising a . p.
    Eigen::Vector3d corner;
    for (int c = 0; c < 3; ++c) corner[c] = a[c] > 0 ? lo[c] : hi[c];
    return out.norm() + a.dot(corner) + b;
  }
};

// Runs BODY once per instruction set compiled in and supported here; returns how many.
template <class Body>
int ForEachTarget(Body&& body) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  for (std::int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    body(hwy::TargetName(t));
  }
  hwy::SetSupportedTargetsForTest(0);
  return int(targets.size());
}

TEST(BatchDistances, MatchTheExactAffineFieldAndTheScalarLookupOnEveryInstructionSet) {
  const AffineField af;
  // A rotation about a skew axis and a translation: points of A in B's frame.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.004, -0.003, 0.02);
  BatchTransform X;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) X.r[3 * i + j] = float(R(i, j));
    X.t[i] = float(t[i]);
  }
  // Points whose image lands inside or outside the box, plus a NaN and an infinite point;
  // 1003 of them, not a multiple of any vector width. (A point on the box's faces may fall
  // either side under another rounding of its transform: see LastGridPlanes below.)
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.15);
  std::vector<float> x, y, z;
  std::vector<Eigen::Vector3d> p_B;
  auto add_B = [&](const Eigen::Vector3d& q) {  // a point given in B's frame
    const Eigen::Vector3d p = R.transpose() * (q - t);
    x.push_back(float(p.x()));
    y.push_back(float(p.y()));
    z.push_back(float(p.z()));
    p_B.push_back(q);
  };
  while (p_B.size() < 1001) add_B(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.6);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  x.push_back(nan), y.push_back(0), z.push_back(0);
  x.push_back(inf), y.push_back(0), z.push_back(0);
  const int n = int(x.size());
  std::vector<std::int32_t> reversed(n);
  for (int k = 0; k < n; ++k) reversed[k] = n - 1 - k;
  // Runs of consecutive points (read with plain loads) between scattered ones (gathered).
  std::vector<std::int32_t> mixed(n);
  for (int k = 0; k < n; ++k) mixed[k] = (k / 48) % 2 ? (k * 7919) % n : k;

  int inside = 0;
  const int targets = ForEachTarget([&](const char* target) {
    SCOPED_TRACE(target);
    std::vector<float> d(n), d_indexed(n);
    BatchDistances(af.field, X, x.data(), y.data(), z.data(), nullptr, n, d.data());
    BatchDistances(af.field, X, x.data(), y.data(), z.data(), reversed.data(), n, d_indexed.data());
    std::vector<float> d_mixed(n);
    BatchDistances(af.field, X, x.data(), y.data(), z.data(), mixed.data(), n, d_mixed.data());
    for (int k = 0; k < n; ++k) ASSERT_EQ(d_mixed[k], d[mixed[k]]) << k;
    inside = 0;
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(d_indexed[n - 1 - k], d[k]) << k;  // rounded alike wherever it is in the batch
      float scalar_p[3];
      for (int c = 0; c < 3; ++c) {
        scalar_p[c] = X.r[3 * c] * x[k] + X.r[3 * c + 1] * y[k] + X.r[3 * c + 2] * z[k] + X.t[c];
      }
      const float scalar = af.field.Distance(scalar_p[0], scalar_p[1], scalar_p[2]);
      if (k >= 1001) {  // NaN and infinite points are never in contact
        EXPECT_EQ(d[k], inf);
        EXPECT_EQ(scalar, inf);
        continue;
      }
      // Float rounding of the transform (|p| < 0.1 m) and of the interpolation.
      EXPECT_NEAR(d[k], scalar, 2e-6) << k;
      EXPECT_NEAR(d[k], af.Exact(p_B[k]), 2e-6) << k;
      if (af.field.Inside(p_B[k])) ++inside;
    }
  });
  EXPECT_GE(targets, 1);
  EXPECT_GT(inside, 100);  // both branches exercised
  EXPECT_LT(inside, 900);
}

// Points on the grid's last planes interpolate in the last cell (t = 1), as the scalar lookup.
TEST(BatchDistances, LastGridPlanesUseTheLastCell) {
  const AffineField af;
  const Eigen::Vector3d lo = af.origin, hi = af.upper();
  const std::vector<Eigen::Vector3d> points = {hi, lo, {hi.x(), lo.y(), hi.z()}, {lo.x(), hi.y(), 0.5 * (lo.z() + hi.z())},
                                               {0.5 * (lo.x() + hi.x()), hi.y(), lo.z()}};
  std::vector<float> x, y, z;
  for (int copy = 0; copy < 8; ++copy) {  // fill whole vectors, whatever the width
    for (const Eigen::Vector3d& p : points) {
      x.push_back(float(p.x()));
      y.push_back(float(p.y()));
      z.push_back(float(p.z()));
    }
  }
  ForEachTarget([&](const char* target) {
    SCOPED_TRACE(target);
    std::vector<float> d(x.size());
    BatchDistances(af.field, kIdentityTransform, x.data(), y.data(), z.data(), nullptr, int(x.size()), d.data());
    for (std::size_t k = 0; k < x.size(); ++k) {
      const Eigen::Vector3d p(x[k], y[k], z[k]);
      EXPECT_NEAR(d[k], af.a.dot(p) + af.b, 1e-6) << k;
    }
  });
}

TEST(BatchDistances, AnEmptyFieldIsNeverInContact) {
  const DistanceField empty;
  const float x[5] = {0, 1, 2, 3, 4};
  float d[5];
  BatchDistances(empty, kIdentityTransform, x, x, x, nullptr, 5, d);
  for (float v : d) EXPECT_EQ(v, std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace contactlab
