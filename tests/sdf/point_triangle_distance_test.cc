// Exact point-triangle distance against dense sampling of the triangle (sec. 2.3).
#include "sdf/point_triangle_distance.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>

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

TEST(PointTriangleDistance, FaceRegionIsPlaneDistance) {
  const Eigen::Vector3d a(0, 0, 0.2), b(1, 0, 0.2), c(0, 1, 0.2), p(0.2, 0.3, -0.45);
  EXPECT_NEAR(std::sqrt(PointTriangleDistanceSquared(p.data(), a.data(), b.data(), c.data())), 0.65, 1e-14);
}

}  // namespace
}  // namespace contactlab
