// Exact point-triangle distance against dense sampling of the triangle (sec. 2.3).
#include "sdf/point_triangle_distance.h"
#include "sdf/point_triangle_batch.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

namespace contactlab {
namespace {

// Minimum distance from P to a dense barycentric sampling of the triangle, and the sampling's
// resolution (an upper bound on how far the true closest point is from a sample).
double SampledDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       const Eigen::Vector3d& c, int n) {
  double best = 1e300;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const Eigen::Vector3d q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
      best = std::min(best, (p - q).norm());
    }
  return best;
}

TEST(PointTriangleDistance, MatchesDenseSamplingInEveryRegion) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 300;
  for (int s = 0; s < 300; ++s) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Eigen::Vector3d p = 1.5 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    const double d = std::sqrt(PointTriangleDistanceSquared(p.data(), a.data(), b.data(), c.data()));
    const double sampled = SampledDistance(p, a, b, c, n);
    const double step = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    EXPECT_LE(d, sampled + 1e-12) << "seed sample " << s;
    EXPECT_GE(d, sampled - step) << "seed sample " << s;
  }
}

TEST(PointTriangleDistance, DegenerateTrianglesAreTheirEdges) {
  const Eigen::Vector3d p(0.25, 1.0 / 3, 0.7);
  // Collinear corners: the segment from (0,0,0) to (1,0,0).
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0.5, 0, 0);
  EXPECT_NEAR(std::sqrt(PointTriangleDistanceSquared(p.data(), a.data(), b.data(), c.data())),
              std::hypot(1.0 / 3, 0.7), 1e-12);
  // All corners at one point.
  EXPECT_NEAR(std::sqrt(PointTriangleDistanceSquared(p.data(), b.data(), b.data(), b.data())), (p - b).norm(),
              1e-12);
  // Two equal corners.
  EXPECT_NEAR(std::sqrt(PointTriangleDistanceSquared(p.data(), a.data(), a.data(), b.data())),
              std::hypot(1.0 / 3, 0.7), 1e-12);
}

// The masked (vector) form on every instruction set against the branching one and against the
// sampled triangle, for points in all seven regions of random (also obtuse and slender)
// triangles, and an odd count so the padded last vector is used.
TEST(PointTriangleDistance, BatchEqualsTheScalarRegionsOnEveryInstructionSet) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  int regions_seen[7] = {0};
  for (int trial = 0; trial < 200; ++trial) {
    double tri[9];
    for (double& v : tri) v = u(rng);
    if (trial % 4 == 0) {  // slender: C close to the segment AB
      for (int a = 0; a < 3; ++a) tri[6 + a] = 0.5 * (tri[a] + tri[3 + a]) + 0.01 * u(rng);
    }
    const int n = 37;
    std::vector<double> x(n), y(n), z(n), out(n);
    for (int i = 0; i < n; ++i) x[i] = 1.5 * u(rng), y[i] = 1.5 * u(rng), z[i] = 1.5 * u(rng);
    for (std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      PointsTriangleDistancesSquared(tri, x.data(), y.data(), z.data(), n, out.data());
      for (int i = 0; i < n; ++i) {
        const double p[3] = {x[i], y[i], z[i]};
        const double ref = PointTriangleDistanceSquared(p, tri, tri + 3, tri + 6);
        ASSERT_NEAR(out[i], ref, 1e-12 * (1 + ref)) << hwy::TargetName(target) << " trial " << trial << " point " << i;
      }
    }
    hwy::SetSupportedTargetsForTest(0);
    // Which region each point falls in (closest point's barycentric zeros), to show all occur.
    const Eigen::Vector3d A(tri[0], tri[1], tri[2]), B(tri[3], tri[4], tri[5]), C(tri[6], tri[7], tri[8]);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p(x[i], y[i], z[i]);
      const double d = std::sqrt(out[i]);
      const double sampled = SampledDistance(p, A, B, C, 64);
      ASSERT_LE(d, sampled + 1e-12);
      const double da = (p - A).norm(), db = (p - B).norm(), dc = (p - C).norm();
      const double eps = 1e-9;
      if (std::abs(d - da) < eps) ++regions_seen[0];
      else if (std::abs(d - db) < eps) ++regions_seen[1];
      else if (std::abs(d - dc) < eps) ++regions_seen[2];
      else {
        const double ab = std::sqrt(internal::PointSegmentDistanceSquared(p.data(), A.data(), B.data()));
        const double ac = std::sqrt(internal::PointSegmentDistanceSquared(p.data(), A.data(), C.data()));
        const double bc = std::sqrt(internal::PointSegmentDistanceSquared(p.data(), B.data(), C.data()));
        if (std::abs(d - ab) < eps) ++regions_seen[3];
        else if (std::abs(d - ac) < eps) ++regions_seen[4];
        else if (std::abs(d - bc) < eps) ++regions_seen[5];
        else ++regions_seen[6];
      }
    }
  }
  for (int r = 0; r < 7; ++r) EXPECT_GT(regions_seen[r], 10) << "region " << r;
}

TEST(PointTriangleDistance, FaceRegionIsPlaneDistance) {
  const Eigen::Vector3d a(0, 0, 0.2), b(1, 0, 0.2), c(0, 1, 0.2), p(0.2, 0.3, -0.45);
  EXPECT_NEAR(std::sqrt(PointTriangleDistanceSquared(p.data(), a.data(), b.data(), c.data())), 0.65, 1e-14);
}

}  // namespace
}  // namespace contactlab
