// The inner-sphere packing (baselines/inner_spheres/sphere_packing.h) on shapes with a closed-form
// distance and volume: asked for 90 % it fills 90 % of a box, a ball and a torus, measured as the
// exact sum of its spheres' volumes against the closed-form volume, with every pair of spheres
// checked disjoint and every sphere checked inside against the closed-form distance, by brute
// force. And why candidates on the grid points alone stop near 80 %: the voids they leave hold
// spheres whose centres are no grid point.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "baselines/inner_spheres/sphere_packing.h"
#include "contact/test_shells.h"

namespace contactlab {
namespace {

constexpr double kPi = std::numbers::pi;

// A shape: its exact signed distance (negative inside), its volume and a box around it.
struct Shape {
  std::function<double(const Eigen::Vector3d&)> phi;
  double volume;
  Eigen::Vector3d lo, hi;
};

// A box with half-extents that are not exact in binary.
Shape Box() {
  const Eigen::Vector3d e(0.03, 0.02 / 3 * 2, 0.0125);
  return {[e](const Eigen::Vector3d& p) {
            const Eigen::Vector3d q = p.cwiseAbs() - e;
            return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
          },
          8 * e.prod(), (-e.array() - 0.003).matrix(), (e.array() + 0.003).matrix()};
}

// A ball whose centre is a grid point of a field of spacing 0.001 (its box starts 17 cells off).
Shape Ball() {
  const double R = 0.02 / 3 * 2;
  return {[R](const Eigen::Vector3d& p) { return p.norm() - R; }, 4.0 / 3.0 * kPi * R * R * R,
          Eigen::Vector3d::Constant(-0.017), Eigen::Vector3d::Constant(0.017)};
}

// A torus about z: ring radius 0.02, tube radius 0.0075.
Shape Torus() {
  const double R = 0.02, r = 0.0075;
  return {[R, r](const Eigen::Vector3d& p) { return Eigen::Vector2d(p.head<2>().norm() - R, p.z()).norm() - r; },
          2 * kPi * kPi * R * r * r, Eigen::Vector3d(-R - r - 0.003, -R - r - 0.003, -r - 0.003),
          Eigen::Vector3d(R + r + 0.003, R + r + 0.003, r + 0.003)};
}

SpherePacking Pack(const Shape& s, double h, double coverage, bool protosphere = true) {
  SpherePackingOptions o;
  o.max_spheres = 1 << 20;
  o.coverage = coverage;
  o.protosphere = protosphere;
  return BuildSpherePacking(*testing::SampleField(s.phi, s.lo, s.hi, h), s.volume, o, "test");
}

// The exact volume of the spheres over the closed-form volume, after checking that each sphere
// is inside the shape (its exact distance; TOLERANCE: the trilinear interpolation's error where
// the shape's distance is not concave) and that no two overlap: every pair whose extents along x
// meet, found by sorting them (an exhaustive check of all pairs that could touch).
double CheckedCoverage(const SpherePacking& p, const Shape& s, double tolerance = 1e-7) {
  double filled = 0, worst_outside = 0;
  int outside = 0, overlapping = 0;
  for (std::size_t i = 0; i < p.radii.size(); ++i) {
    const double r = p.radii[i];
    if (!(r > 0) || r > -s.phi(p.centers[i]) + tolerance) ++outside;
    worst_outside = std::max(worst_outside, r + s.phi(p.centers[i]));
    filled += 4.0 / 3.0 * kPi * r * r * r;
  }
  std::vector<std::size_t> order(p.radii.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto lo = [&](std::size_t i) { return p.centers[i].x() - p.radii[i]; };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t a = 0; a < order.size(); ++a) {
    const std::size_t i = order[a];
    const double hi = p.centers[i].x() + p.radii[i];
    for (std::size_t b = a + 1; b < order.size() && lo(order[b]) < hi; ++b) {
      const std::size_t j = order[b];
      if ((p.centers[i] - p.centers[j]).norm() < p.radii[i] + p.radii[j] - 1e-9) ++overlapping;
    }
  }
  EXPECT_EQ(outside, 0) << "spheres reaching outside the shape, by up to " << worst_outside;
  EXPECT_EQ(overlapping, 0) << "pairs of spheres overlapping";
  return filled / s.volume;
}

TEST(SpherePackingFill, ReachesNinetyPercentOfABoxAndABall) {
  // Flat faces are the hard part: the wedges between the spheres and a face take ever smaller
  // spheres (about 280,000 here, the smallest a tenth of a cell).
  const Shape box = Box();
  const SpherePacking p = Pack(box, 0.0005, 0.9);
  const double coverage = CheckedCoverage(p, box);
  std::printf("box: %zu spheres fill %.4f\n", p.radii.size(), coverage);
  EXPECT_GE(coverage, 0.9);
  EXPECT_NEAR(coverage, p.Coverage(), 1e-12);
  const Shape ball = Ball();
  const SpherePacking q = Pack(ball, 0.001, 0.9);
  const double ball_coverage = CheckedCoverage(q, ball);
  std::printf("ball: %zu spheres fill %.4f\n", q.radii.size(), ball_coverage);
  EXPECT_GE(ball_coverage, 0.9);
}

TEST(SpherePackingFill, FillsATorusPastTheGridPointsCeiling) {
  // A curved body whose distance is not concave everywhere (the inner side of the ring): inside
  // up to the trilinear interpolation's error, a small fraction of a cell.
  const Shape torus = Torus();
  const SpherePacking grid = Pack(torus, 0.001, 0.84, false);
  const SpherePacking proto = Pack(torus, 0.001, 0.84);
  const double grid_coverage = CheckedCoverage(grid, torus);
  const double coverage = CheckedCoverage(proto, torus, 0.02 * 0.001);
  std::printf("torus: %zu spheres fill %.4f (grid points only: %zu fill %.4f)\n", proto.radii.size(), coverage,
              grid.radii.size(), grid_coverage);
  EXPECT_GE(coverage, 0.84);
  EXPECT_LT(grid_coverage, 0.8);
}

TEST(SpherePackingFill, GridPointsAloneLeaveVoidsThatHoldSpheres) {
  // Candidates on the grid points only: the packing runs out of candidates (every grid point's
  // free radius is below the smallest sphere, a tenth of a cell) short of the target ...
  const Shape box = Box();
  const double h = 0.001;
  const SpherePacking grid = Pack(box, h, 0.9, /*protosphere=*/false);  // short of 0.9
  const double grid_coverage = CheckedCoverage(grid, box);
  std::printf("grid points only: %zu spheres fill %.4f\n", grid.radii.size(), grid_coverage);
  EXPECT_LT(grid_coverage, 0.85);
  auto field = testing::SampleField(box.phi, box.lo, box.hi, h);
  const Eigen::Vector3i n = field->dims();
  double largest_free = -1;
  for (int k = 0; k < n.z(); ++k) {
    for (int j = 0; j < n.y(); ++j) {
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Vector3d x = field->GridPoint(i, j, k);
        double free = -field->value(i, j, k);
        for (std::size_t s = 0; s < grid.radii.size(); ++s) free = std::min(free, (x - grid.centers[s]).norm() - grid.radii[s]);
        largest_free = std::max(largest_free, free);
      }
    }
  }
  EXPECT_LT(largest_free, 0.1 * h);  // the packing's floor: no grid point is left
  // ... while the voids between its spheres still hold spheres of more than half a cell, centred
  // off the grid: the largest free radius over a grid four times finer.
  double void_radius = 0;
  for (double z = box.lo.z(); z <= box.hi.z(); z += h / 4) {
    for (double y = box.lo.y(); y <= box.hi.y(); y += h / 4) {
      for (double x = box.lo.x(); x <= box.hi.x(); x += h / 4) {
        const Eigen::Vector3d q(x, y, z);
        double free = -box.phi(q);
        if (free <= void_radius) continue;
        for (std::size_t s = 0; s < grid.radii.size() && free > void_radius; ++s) {
          free = std::min(free, (q - grid.centers[s]).norm() - grid.radii[s]);
        }
        void_radius = std::max(void_radius, free);
      }
    }
  }
  std::printf("largest free radius: %.3f cells on the grid points, %.3f cells off them\n", largest_free / h,
              void_radius / h);
  EXPECT_GT(void_radius, 0.5 * h);
}

TEST(SpherePackingFill, PrototypesMoveToLargerSpheresThanTheGridOffers) {
  // The same box: with prototypes the packing passes the grid's ceiling, with fewer spheres
  // for the same volume (each one nearer the centre of its void).
  const Shape box = Box();
  const SpherePacking grid = Pack(box, 0.001, 0.7, false);
  const SpherePacking proto = Pack(box, 0.001, 0.7, true);
  ASSERT_GE(grid.Coverage(), 0.7);
  ASSERT_GE(proto.Coverage(), 0.7);
  EXPECT_LT(proto.radii.size(), grid.radii.size());
}

}  // namespace
}  // namespace contactlab
