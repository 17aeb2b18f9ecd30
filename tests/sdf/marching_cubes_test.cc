// Marching cubes: crack-free, consistently oriented, accurate on a sphere (sec. 2.3).
#include "sdf/marching_cubes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numbers>
#include <random>

#include "sdf_reference.h"

namespace contactlab {
namespace {

using testing::CountEdges;
using testing::EdgeCensus;

TEST(MarchingCubes, TablePolygonsUseEveryCrossedEdgeOnce) {
  const auto& table = MarchingCubesTable();
  for (int mask = 0; mask < 256; ++mask) {
    int used[12] = {};
    for (int n = 0; table[mask][n] >= 0;) {
      const int size = table[mask][n];
      EXPECT_GE(size, 3) << mask;
      EXPECT_LT(table[mask][n + 1], size) << mask;
      for (int s = 0; s < size; ++s) ++used[table[mask][n + 2 + s]];
      n += 2 + size;
    }
    // Exactly the edges whose corners differ in inside-ness, each in one polygon.
    for (int e = 0; e < 12; ++e) {
      const bool crossed = ((mask >> kCubeEdgeCorners[e][0]) & 1) != ((mask >> kCubeEdgeCorners[e][1]) & 1);
      EXPECT_EQ(used[e], crossed ? 1 : 0) << "case " << mask << " edge " << e;
    }
  }
}

TEST(MarchingCubes, RandomFieldsGiveClosedOrientedSurfaces) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1, 1);
  FieldGrid grid;
  grid.origin = Eigen::Vector3d(0.1, -0.2, 1.0 / 3);
  grid.spacing = 0.1;
  grid.dims = Eigen::Vector3i(9, 7, 8);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<float> v(grid.num_points());
    for (auto& x : v) x = u(rng);
    const TriangleMesh m = ExtractIsosurface(v, grid, 0.0, /*close_at_boundary=*/true);
    ASSERT_GT(m.num_triangles(), 0);
    const EdgeCensus c = CountEdges(m);
    EXPECT_EQ(c.boundary, 0) << "trial " << trial;
    EXPECT_EQ(c.nonmanifold, 0) << "trial " << trial;
    EXPECT_EQ(c.inconsistent, 0) << "trial " << trial;
  }
}

TEST(MarchingCubes, SphereIsosurfaceIsAccurateAndFacesOutward) {
  const double R = 0.37;
  FieldGrid grid;
  grid.spacing = 1.0 / 30;
  grid.dims = Eigen::Vector3i::Constant(31);
  grid.origin = Eigen::Vector3d::Constant(-0.5);
  std::vector<float> v(grid.num_points());
  for (int k = 0; k < 31; ++k)
    for (int j = 0; j < 31; ++j)
      for (int i = 0; i < 31; ++i) v[grid.Index(i, j, k)] = float(grid.Point(i, j, k).norm() - R);
  const TriangleMesh m = ExtractIsosurface(v, grid, 0.0);
  const EdgeCensus c = CountEdges(m);
  EXPECT_EQ(c.boundary, 0);
  EXPECT_EQ(c.inconsistent, 0);
  const double h = grid.spacing;
  for (const auto& p : m.vertices) EXPECT_NEAR(p.norm(), R, h * h / R);
  const double volume = 4.0 / 3 * std::numbers::pi * R * R * R;
  EXPECT_LT(m.SignedVolume(), volume);  // chords cut inside a convex surface
  EXPECT_NEAR(m.SignedVolume(), volume, 0.01 * volume);
}

}  // namespace
}  // namespace contactlab
