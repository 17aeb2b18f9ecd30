// Distance fields built from procedural meshes against analytic and brute-force references,
// and the builder's input checks (Barbič & James 2008, sec. 2.3).
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <Eigen/Geometry>
#include <random>

#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "sdf/field_grid.h"
#include "sdf_reference.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BruteForceDistance;
using testing::BruteForceSignedDistance;

// Samples on the grid's boundary faces: one of them is lowered to keep the outside-the-box
// bound conservative (signed_distance_grid.h), so exactness checks skip them.
bool OnBoundary(const DistanceField& f, int i, int j, int k) {
  return i == 0 || j == 0 || k == 0 || i == f.dims().x() - 1 || j == f.dims().y() - 1 || k == f.dims().z() - 1;
}

DistanceFieldOptions Quiet(int resolution, FieldMode mode = FieldMode::kAuto) {
  DistanceFieldOptions o;
  o.resolution = resolution;
  o.mode = mode;
  o.show_progress = false;
  return o;
}

// Largest distance from the mesh to the surface it approximates, measured at triangle
// centroids and edge midpoints by the analytic distance EXACT.
template <typename F>
double DiscretisationError(const TriangleMesh& m, F exact) {
  double e = 0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d& a = m.vertices[t[0]];
    const Eigen::Vector3d& b = m.vertices[t[1]];
    const Eigen::Vector3d& c = m.vertices[t[2]];
    for (const Eigen::Vector3d& p : {Eigen::Vector3d((a + b + c) / 3), Eigen::Vector3d((a + b) / 2),
                                     Eigen::Vector3d((b + c) / 2), Eigen::Vector3d((c + a) / 2)}) {
      e = std::max(e, std::abs(exact(p)));
    }
  }
  return e;
}

TEST(BuildDistanceField, GridCoversThePaddedBoxWithResolutionCellsAlongTheLongestSide) {
  Aabb b;
  b.Extend(Eigen::Vector3d(-1, 0, 0.5));
  b.Extend(Eigen::Vector3d(2, 1.0 / 3, 1));
  const FieldGrid g = MakeFieldGrid(b, 30, 0.1);
  EXPECT_EQ(g.dims.x(), 31);
  EXPECT_NEAR(g.spacing, 3.6 / 30, 1e-12);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(g.origin[a], b.min[a] - 0.3 + 1e-12);
    EXPECT_GE(g.origin[a] + g.spacing * (g.dims[a] - 1), b.max[a] + 0.3 - 1e-12);
  }
}

TEST(BuildDistanceField, SphereFieldMatchesAnalyticDistanceWithinTrilinearAndMeshError) {
  const double R = 0.3;
  const TriangleMesh sphere = MakeSphere(R, 5);
  const DistanceField f = BuildDistanceField(sphere, Quiet(48));
  EXPECT_EQ(f.info().mode, "closed");
  const double h = f.spacing();
  const double mesh_error = DiscretisationError(sphere, [&](const Eigen::Vector3d& p) { return p.norm() - R; });
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  double worst = 0;
  for (int s = 0; s < 3000; ++s) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (p.norm() < 3 * h) continue;  // the distance is not smooth at the centre
    const double trilinear = 3 * h * h / 8 / (p.norm() - std::sqrt(3.0) * h);
    // Beyond the exact band (3 voxels) closest-triangle propagation may pick a triangle a
    // little farther than the closest one (unsigned_distance_grid.h).
    const double propagation = std::abs(p.norm() - R) > (3 - std::sqrt(3.0)) * h ? 0.5 * h : 0.0;
    const double bound = trilinear + mesh_error + propagation + 1e-6;
    const double err = std::abs(f.Distance(p) - (p.norm() - R));
    worst = std::max(worst, err / bound);
    EXPECT_LE(err, bound) << p.transpose();
  }
  RecordProperty("worst_error_over_bound", std::to_string(worst));
}

TEST(BuildDistanceField, BoxGridValuesAreExactSignedDistances) {
  const Eigen::Vector3d half(0.2, 1.0 / 3, 0.1);
  const DistanceField f = BuildDistanceField(MakeBox(half), Quiet(40));
  auto exact = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p.cwiseAbs() - half;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  for (int k = 0; k < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) {
        if (OnBoundary(f, i, j, k)) continue;
        const double e = exact(f.GridPoint(i, j, k));
        ASSERT_NEAR(f.value(i, j, k), e, 1e-6) << i << " " << j << " " << k;
      }
}

TEST(BuildDistanceField, TorusFieldMatchesAnalyticDistanceAtRandomPoints) {
  const double Rt = 0.3, rt = 0.1;
  const TriangleMesh torus = MakeTorus(Rt, rt, 96, 48);
  const DistanceField f = BuildDistanceField(torus, Quiet(56));
  const double h = f.spacing();
  auto exact = [&](const Eigen::Vector3d& p) { return std::hypot(std::hypot(p.x(), p.y()) - Rt, p.z()) - rt; };
  const double mesh_error = DiscretisationError(torus, exact);
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-0.42, 0.42);
  for (int s = 0; s < 3000; ++s) {
    const Eigen::Vector3d p(u(rng), u(rng), 0.3 * u(rng));
    // Trilinear error bound for |Hessian| <= 1/(distance to the tube centre line).
    const double to_axis = std::hypot(std::hypot(p.x(), p.y()) - Rt, p.z());
    const double ring = std::hypot(p.x(), p.y());
    if (to_axis < 3 * h || ring < 3 * h) continue;  // creases of the distance function
    const double curvature = 1 / (to_axis - std::sqrt(3.0) * h) + 1 / (ring - std::sqrt(3.0) * h);
    const double bound = 3 * h * h / 8 * curvature + mesh_error + 1e-6;
    EXPECT_NEAR(f.Distance(p), exact(p), bound) << p.transpose();
  }
}

TEST(BuildDistanceField, GridValuesAreExactInTheBandAndNeverBelowTheTrueDistance) {
  const TriangleMesh torus = MakeTorus(0.3, 0.08, 48, 24);
  const DistanceField f = BuildDistanceField(torus, Quiet(32));
  const double h = f.spacing();
  std::mt19937 rng(29);
  int in_band = 0;
  double far_excess = 0;
  for (int s = 0; s < 1500; ++s) {
    const int i = int(rng() % f.dims().x()), j = int(rng() % f.dims().y()), k = int(rng() % f.dims().z());
    if (OnBoundary(f, i, j, k)) continue;
    const double ref = BruteForceSignedDistance(torus, f.GridPoint(i, j, k));
    const double v = f.value(i, j, k);
    if (std::abs(ref) > 1e-9) {
      EXPECT_EQ(v < 0, ref < 0) << i << " " << j << " " << k;
    }
    if (std::abs(ref) <= 3 * h) {
      ++in_band;
      EXPECT_NEAR(v, ref, 1e-6 + 1e-6 * std::abs(ref));
    } else {
      EXPECT_GE(std::abs(v), std::abs(ref) - 1e-6);
      far_excess = std::max(far_excess, (std::abs(v) - std::abs(ref)) / h);
    }
  }
  EXPECT_GT(in_band, 50);
  EXPECT_LT(far_excess, 0.25);  // propagation error far from the surface, in voxels
  RecordProperty("far_excess_voxels", std::to_string(far_excess));
}

TEST(BuildDistanceField, OutsideBoxBoundNeverOverestimates) {
  const TriangleMesh torus = MakeTorus(0.3, 0.1, 48, 24);
  const DistanceField f = BuildDistanceField(torus, Quiet(24));
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-2, 2);
  int outside = 0;
  for (int s = 0; s < 600; ++s) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (f.Inside(p)) continue;
    ++outside;
    EXPECT_LE(f.Distance(p), BruteForceDistance(torus, p) + 1e-6) << p.transpose();
  }
  EXPECT_GT(outside, 300);
}

// A square sheet (two triangles) in the plane z = 0: the soup field is the distance to the
// sheet minus the offset, its zero set the rounded slab around it.
TEST(BuildDistanceField, SoupFieldZeroSetIsTheOffsetSurface) {
  TriangleMesh sheet;
  sheet.name = "sheet";
  sheet.vertices = {{-0.3, -0.3, 0}, {0.3, -0.3, 0}, {0.3, 0.3, 0}, {-0.3, 0.3, 0}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  const DistanceField f = BuildDistanceField(sheet, Quiet(40));
  EXPECT_EQ(f.info().mode, "soup");
  const double h = f.spacing();
  EXPECT_NEAR(f.info().offset, 1.5 * h, 1e-12);
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(-0.33, 0.33);
  int checked = 0;
  for (int s = 0; s < 2000; ++s) {
    const Eigen::Vector3d p(u(rng), u(rng), 0.3 * u(rng));
    const double distance = BruteForceDistance(sheet, p);
    // The field has a crease on the sheet itself (the medial surface of the slab), which
    // trilinear interpolation rounds off within a cell; check the points a cell away from it.
    if (distance < std::sqrt(3.0) * h || !f.Inside(p)) continue;
    ++checked;
    // Marching cubes places the offset surface within a fraction of a voxel (worst at the
    // slab's rims, whose radius of curvature is the offset itself).
    EXPECT_NEAR(f.Distance(p), distance - f.info().offset, 0.5 * h) << p.transpose();
  }
  EXPECT_GT(checked, 500);
  EXPECT_GT(f.boundary_min(), 0);
}

// An icosphere with one triangle removed: its offset surface has an outer and an inner shell
// joined nowhere (the hole is narrower than twice the offset); the inner one is dropped, so
// the centre is inside, at the outer shell's distance R + offset (were the inner shell kept,
// the two shells' windings would cancel and the centre would be outside).
TEST(BuildDistanceField, SoupDropsComponentsEnclosedByOthers) {
  TriangleMesh open = MakeSphere(0.3, 3);
  open.name = "sphere with a hole";
  open.triangles.pop_back();
  const DistanceField f = BuildDistanceField(open, Quiet(32));
  EXPECT_EQ(f.info().mode, "soup");
  EXPECT_NEAR(f.Distance(Eigen::Vector3d::Zero()), -(0.3 + f.info().offset), 0.01);
  EXPECT_GT(f.Distance(f.box().max), 0);
}

TEST(BuildDistanceField, BadResolutionIsRejected) {
  const TriangleMesh s = MakeSphere(0.1, 1);
  EXPECT_THROW(BuildDistanceField(s, Quiet(4)), Error);
  EXPECT_THROW(BuildDistanceField(s, Quiet(5000)), Error);
}

TEST(BuildDistanceField, EmptyMeshIsRejectedNamingIt) {
  TriangleMesh empty;
  empty.name = "nothing.obj";
  try {
    BuildDistanceField(empty, Quiet(16));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.obj"), std::string::npos) << e.what();
  }
}

TEST(BuildDistanceField, MeshWhoseVerticesAllCoincideIsRejectedNotGivenATinyGrid) {
  TriangleMesh point;
  point.name = "point.obj";
  point.vertices = {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1, 1)};
  point.triangles = {Eigen::Vector3i(0, 1, 2)};
  try {
    BuildDistanceField(point, Quiet(32));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("point.obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("zero extent"), std::string::npos) << e.what();
  }
  // A flat mesh (zero extent along one axis only) still gets its field.
  TriangleMesh flat;
  flat.name = "flat.obj";
  flat.vertices = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  flat.triangles = {Eigen::Vector3i(0, 1, 2)};
  EXPECT_GT(BuildDistanceField(flat, Quiet(16)).num_samples(), 16 * 16);
}

TEST(BuildDistanceField, ForcedClosedModeOnASoupIsRejected) {
  TriangleMesh open = MakeSphere(0.3, 2);
  open.name = "open sphere";
  open.triangles.pop_back();
  try {
    BuildDistanceField(open, Quiet(16, FieldMode::kClosed));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not watertight"), std::string::npos) << e.what();
  }
}

TEST(BuildDistanceField, ModeNamesParseAndUnknownOnesAreRejected) {
  EXPECT_EQ(ParseFieldMode("auto", "x"), FieldMode::kAuto);
  EXPECT_EQ(ParseFieldMode("closed", "x"), FieldMode::kClosed);
  EXPECT_EQ(ParseFieldMode("soup", "x"), FieldMode::kSoup);
  EXPECT_THROW(ParseFieldMode("signed", "--mode"), Error);
}

}  // namespace
}  // namespace contactlab

namespace contactlab {
namespace {

// A field build started from a task whose group has been cancelled still completes.
TEST(BuildDistanceField, CompletesInsideACancelledTaskGroup) {
  const TriangleMesh mesh = MakeTorus(0.3, 0.1, 48, 24);
  DistanceFieldOptions options;
  options.resolution = 32;
  options.show_progress = false;
  const DistanceField expected = BuildDistanceField(mesh, options);
  DistanceField built;
  tbb::task_group_context outer;
  tbb::parallel_for(
      0, 1,
      [&](int) {
        outer.cancel_group_execution();
        built = BuildDistanceField(mesh, options);
      },
      outer);
  EXPECT_EQ(built.values(), expected.values());
}

}  // namespace
}  // namespace contactlab
