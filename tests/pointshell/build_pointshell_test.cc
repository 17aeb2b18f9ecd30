#include "pointshell/build_pointshell.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <tbb/global_control.h>

#include <cmath>

#include "geometry/procedural_shapes.h"
#include "pointshell/analytic_fields.h"
#include "pointshell/level_set_sampling.h"
#include "pointshell/pointshell_io.h"
#include "pointshell/pointshell_quality.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::SampledField;
using testing::SampledSphere;

constexpr double kRadius = 0.3;

// Sphere of radius 0.3 in [-0.5, 0.5]^3, 49^3 samples (spacing 1/48 m).
const DistanceField& Sphere() {
  static const DistanceField field = SampledSphere(kRadius, 0.5, 49);
  return field;
}

PointshellOptions Options(PointshellMethod method, int points, int levels, std::uint64_t seed = 7) {
  PointshellOptions o;
  o.method = method;
  o.num_points = points;
  o.num_levels = levels;
  o.seed = seed;
  o.show_progress = false;
  return o;
}

// 4096 points in 4 levels (64, 256, 1024, 4096), built once.
const Pointshell& RepulsionShell() {
  static const Pointshell shell = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 4096, 4));
  return shell;
}

using testing::ErrorOf;

bool Identical(const Pointshell& a, const Pointshell& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z && a.nx == b.nx && a.ny == b.ny && a.nz == b.nz &&
         a.level_point_end == b.level_point_end && a.level_node_begin == b.level_node_begin &&
         a.node_point == b.node_point && a.node_radius == b.node_radius && a.child_begin == b.child_begin &&
         a.node_parent == b.node_parent;
}

// Stated bound: every repulsion level of >= 64 points has a nearest-neighbour spacing CV below
// 0.12 (measured ~0.03-0.07), while random sampling gives ~0.5.
TEST(BuildPointshell, RepulsionSpacingIsNearUniformAndFarBetterThanRandom) {
  const PointshellQuality rep = AssessPointshell(RepulsionShell(), &Sphere(), {20000});
  const Pointshell random = BuildPointshell(Sphere(), Options(PointshellMethod::kRandom, 4096, 4));
  const PointshellQuality rnd = AssessPointshell(random, &Sphere(), {20000});
  ASSERT_EQ(rep.levels.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_LT(rep.levels[i].spacing_cv, 0.12);
    EXPECT_GT(rnd.levels[i].spacing_cv, 0.35);
    EXPECT_LT(rep.levels[i].spacing_cv, 0.25 * rnd.levels[i].spacing_cv);
    // Spacing tracks sqrt(area / n): within 20% of the hexagonal-lattice spacing 1.075 sqrt(A/n).
    const double hex = 1.0746 * std::sqrt(rep.area / rep.levels[i].points);
    EXPECT_NEAR(rep.levels[i].spacing_mean, hex, 0.2 * hex);
    // No gaps: the covering radius stays below 1.2 spacings, half the random one or less.
    EXPECT_LT(rep.levels[i].covering_radius, 1.2 * rep.levels[i].spacing_mean);
    EXPECT_LT(rep.levels[i].covering_radius, 0.7 * rnd.levels[i].covering_radius);
  }
  // The area estimate is within 2% of the offset sphere's area.
  const double r = kRadius + RepulsionShell().offset;
  EXPECT_NEAR(rep.area, 4 * M_PI * r * r, 0.02 * 4 * M_PI * r * r);
}

// Angle between two vectors in degrees, accurate near 0.
double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

// Stated tolerances. Normals: unit (1e-6); inward, within 3.5 degrees of the exact direction
// to the centre (the trilinear gradient's own error: its scale is h / r = 0.067 rad = 3.8
// degrees here, measured worst 2.6); orthogonal to the level set, within 1e-3 degrees of the
// field gradient at the point. Points on the level set within 1e-5 grid spacings.
TEST(BuildPointshell, NormalsAreUnitInwardAndOrthogonalToTheLevelSet) {
  const Pointshell& s = RepulsionShell();
  const double h = Sphere().spacing();
  EXPECT_NEAR(s.offset, 0.5 * h, 1e-15);
  double worst_centre = 0, worst_gradient = 0, worst_distance = 0;
  for (int i = 0; i < s.num_points(); ++i) {
    const Eigen::Vector3d p(s.x[i], s.y[i], s.z[i]), n(s.nx[i], s.ny[i], s.nz[i]);
    ASSERT_NEAR(n.norm(), 1.0, 1e-6);
    const double to_centre = AngleDeg(n, -p);
    Eigen::Vector3d g;
    const double d = Sphere().DistanceAndGradient(p, &g);
    const double to_gradient = AngleDeg(n, -g);
    worst_centre = std::max(worst_centre, to_centre);
    worst_gradient = std::max(worst_gradient, to_gradient);
    worst_distance = std::max(worst_distance, std::abs(d - s.offset));
  }
  EXPECT_LT(worst_centre, 3.5);
  EXPECT_LT(worst_gradient, 1e-3);
  EXPECT_LT(worst_distance, 1e-5 * h);
}

TEST(BuildPointshell, LevelCountsGrowByTheBranchingFactor) {
  EXPECT_EQ(RepulsionShell().level_point_end, (std::vector<std::int32_t>{64, 256, 1024, 4096}));
  EXPECT_EQ(NestedLevelEnds(256000, 5, 4, "t"), (std::vector<std::int32_t>{1000, 4000, 16000, 64000, 256000}));
  EXPECT_EQ(NestedLevelEnds(100, 3, 2, "t"), (std::vector<std::int32_t>{25, 50, 100}));
  EXPECT_EQ(NestedLevelEnds(5, 1, 4, "t"), (std::vector<std::int32_t>{5}));
}

// Nesting: coarse levels are frozen while finer ones are added, so the first 256 points of the
// 4-level shell are bit-identical to a 2-level shell of 256 points with the same seed.
TEST(BuildPointshell, CoarseLevelsAreFrozenWhileFinerLevelsAreAdded) {
  const Pointshell coarse = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 256, 2));
  const Pointshell& fine = RepulsionShell();
  ASSERT_EQ(coarse.num_points(), 256);
  for (int i = 0; i < 256; ++i) {
    ASSERT_EQ(coarse.x[i], fine.x[i]) << i;
    ASSERT_EQ(coarse.y[i], fine.y[i]) << i;
    ASSERT_EQ(coarse.z[i], fine.z[i]) << i;
  }
}

TEST(BuildPointshell, SameSeedGivesBitIdenticalShellsForAnyThreadCount) {
  const Pointshell a = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 1024, 3, 99));
  Pointshell b;
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    b = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 1024, 3, 99));
  }
  EXPECT_TRUE(Identical(a, b));
  const Pointshell c = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 1024, 3, 100));
  EXPECT_NE(a.x, c.x);
  EXPECT_EQ(a.seed, 99u);
  EXPECT_EQ(a.method, "repulsion");
  EXPECT_EQ(a.source, "sphere");
}

TEST(BuildPointshell, AlternativeMethodsGiveValidTreesWithInwardNormals) {
  const TriangleMesh mesh = MakeSphere(kRadius, 4);  // 2562 vertices
  PointshellOptions voxel = Options(PointshellMethod::kVoxel, 2000, 3);
  for (const auto& o : {voxel, Options(PointshellMethod::kRandom, 2000, 3), Options(PointshellMethod::kVertices, 2000, 3)}) {
    SCOPED_TRACE(PointshellMethodName(o.method));
    const Pointshell s = BuildPointshell(Sphere(), o, &mesh);
    EXPECT_NO_THROW(ValidatePointshell(s, "test"));
    EXPECT_EQ(s.method, PointshellMethodName(o.method));
    EXPECT_EQ(s.num_levels(), 3);
    if (o.method != PointshellMethod::kVoxel) {
      EXPECT_EQ(s.num_points(), 2000);
    }
    for (int i = 0; i < s.num_points(); ++i) {
      const Eigen::Vector3d p(s.x[i], s.y[i], s.z[i]), n(s.nx[i], s.ny[i], s.nz[i]);
      ASSERT_LT(AngleDeg(n, -p), 3.5) << i;
      // Voxel centres are within half a voxel diagonal of the level set; the others on it.
      const double d = Sphere().Distance(p) - s.offset;
      if (o.method == PointshellMethod::kVoxel) {
        ASSERT_LT(std::abs(d), 0.5 * std::sqrt(3.0) * 0.05) << i;
      } else {
        ASSERT_LT(std::abs(d), 1e-5 * Sphere().spacing()) << i;
      }
    }
  }
  // The voxel count follows the requested number of points (side from the area estimate).
  const Pointshell v = BuildPointshell(Sphere(), voxel);
  EXPECT_GT(v.num_points(), 1000);
  EXPECT_LT(v.num_points(), 4000);
}

TEST(BuildPointshell, BadParametersGiveClearErrors) {
  const auto build = [](PointshellOptions o) { return [o] { BuildPointshell(Sphere(), o); }; };
  EXPECT_NE(ErrorOf(build(Options(PointshellMethod::kRepulsion, 0, 1))).find("number of points must be at least 1"),
            std::string::npos);
  EXPECT_NE(ErrorOf(build(Options(PointshellMethod::kRepulsion, 10, 4))).find("cannot fill 4 levels"),
            std::string::npos);
  EXPECT_NE(ErrorOf(build(Options(PointshellMethod::kRepulsion, 64, 0))).find("levels must be at least 1"),
            std::string::npos);
  PointshellOptions o = Options(PointshellMethod::kRepulsion, 64, 2);
  o.branching = 1;
  EXPECT_NE(ErrorOf(build(o)).find("branching factor"), std::string::npos);
  // The level set d = 0.25 would reach the box (boundary values >= 0.2).
  o = Options(PointshellMethod::kRepulsion, 64, 2);
  o.offset = 0.25;
  EXPECT_NE(ErrorOf(build(o)).find("reaches the box"), std::string::npos);
  // d = -0.4 lies below every sample: empty level set.
  o.offset = -0.4;
  EXPECT_NE(ErrorOf(build(o)).find("level set d = offset is empty"), std::string::npos);
  o.offset = std::nan("");
  EXPECT_NE(ErrorOf(build(o)).find("not finite"), std::string::npos);
  // Vertices without a mesh.
  EXPECT_NE(ErrorOf(build(Options(PointshellMethod::kVertices, 64, 1))).find("needs the triangle mesh"),
            std::string::npos);
  // A field with no zero crossing (a sphere entirely outside the box).
  const DistanceField outside = SampledField(
      [](const Eigen::Vector3d& p) { return (p - Eigen::Vector3d(2, 0, 0)).norm() - 0.3; }, 0.5, 9, "far sphere");
  const std::string msg = ErrorOf([&] { BuildPointshell(outside, Options(PointshellMethod::kRepulsion, 64, 1)); });
  EXPECT_NE(msg.find("far sphere"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no zero crossing"), std::string::npos) << msg;
  EXPECT_NE(ErrorOf([] { ParsePointshellMethod("blue", "--method"); }).find("unknown pointshell method"),
            std::string::npos);
  EXPECT_EQ(ParsePointshellMethod("voxel", "x"), PointshellMethod::kVoxel);
}

TEST(LevelSetSampling, ProjectionLandsOnTheLevelSetAlongTheGradient) {
  Eigen::Vector3d p(0.1, 0.2, -0.15), g;
  const double delta = 0.01;
  ASSERT_TRUE(ProjectOntoLevelSet(Sphere(), delta, 1e-9, 20, &p, &g));
  EXPECT_NEAR(Sphere().DistanceAndGradient(p, nullptr), delta, 1e-9);
  // Radial motion on a sphere: the direction from the centre is kept (to the interpolation error).
  EXPECT_GT(p.normalized().dot(Eigen::Vector3d(0.1, 0.2, -0.15).normalized()), 0.999);
}

}  // namespace
}  // namespace contactlab

namespace contactlab {
namespace {

// A build started from a task whose group has been cancelled (as when another job of a
// parallel sweep fails) still completes, identical to an ordinary build.
TEST(BuildPointshell, CompletesInsideACancelledTaskGroup) {
  const Pointshell expected = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 1024, 3, 5));
  Pointshell built;
  tbb::task_group_context outer;
  tbb::parallel_for(
      0, 1,
      [&](int) {
        outer.cancel_group_execution();
        built = BuildPointshell(Sphere(), Options(PointshellMethod::kRepulsion, 1024, 3, 5));
      },
      outer);
  EXPECT_EQ(built.x, expected.x);
  EXPECT_EQ(built.node_radius, expected.node_radius);
}

}  // namespace
}  // namespace contactlab
