// Distance fields of the real meshes the repository ships (data/meshes) against brute-force references: every closed mesh
// (exact distance to all triangles, winding-number sign) and the polygon soups (closed zero
// set, offset-surface distances, sign far inside and outside). Barbič & James 2008, sec. 2.3.
#include <gtest/gtest.h>

#include <random>

#include "geometry/mesh_io.h"
#include "sdf/build_distance_field.h"
#include "sdf/marching_cubes.h"
#include "sdf/field_grid.h"
#include "sdf_reference.h"
#include "test_support.h"

namespace contactlab {
namespace {

using testing::BruteForceDistance;
using testing::BruteForceSignedDistance;

DistanceFieldOptions Quiet(int resolution, FieldMode mode) {
  DistanceFieldOptions o;
  o.resolution = resolution;
  o.mode = mode;
  o.show_progress = false;
  return o;
}

std::string TestName(const ::testing::TestParamInfo<std::string>& info) {
  std::string s = info.param;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

class ClosedSharedMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(ClosedSharedMesh, SignAndDistanceMatchBruteForce) {
  const std::filesystem::path path = testing::TestMesh(GetParam());
  const TriangleMesh mesh = LoadMesh(path);
  const DistanceField f = BuildDistanceField(mesh, Quiet(40, FieldMode::kClosed));
  const double h = f.spacing();
  std::mt19937 rng(41);
  // Grid samples: exact in the band, never below the truth, sign of the winding number.
  int checked_sign = 0;
  for (int s = 0; s < 80; ++s) {
    // Interior grid points (one boundary sample is lowered on purpose, signed_distance_grid.h).
    const int i = 1 + int(rng() % (f.dims().x() - 2)), j = 1 + int(rng() % (f.dims().y() - 2)),
              k = 1 + int(rng() % (f.dims().z() - 2));
    const Eigen::Vector3d p = f.GridPoint(i, j, k);
    const double ref = BruteForceSignedDistance(mesh, p);
    const double v = f.value(i, j, k);
    if (std::abs(ref) > 1e-6 * h) {
      ++checked_sign;
      EXPECT_EQ(v < 0, ref < 0) << "grid point " << i << " " << j << " " << k << " ref " << ref << " value " << v;
    }
    if (std::abs(ref) <= 3 * h) {
      EXPECT_NEAR(std::abs(v), std::abs(ref), 1e-5 * h) << p.transpose();
    } else {
      EXPECT_GE(std::abs(v), std::abs(ref) * (1 - 1e-6)) << p.transpose();
    }
    EXPECT_LE(std::abs(v), std::abs(ref) + 0.5 * h) << p.transpose();
  }
  EXPECT_GT(checked_sign, 60);
  // Points near the surface (mesh vertices pushed along random directions): the trilinear
  // value is a convex combination of samples within sqrt(3) h of the point.
  for (int s = 0; s < 80; ++s) {
    const Eigen::Vector3d dir3 = Eigen::Vector3d::Random().normalized();
    const Eigen::Vector3d p = mesh.vertices[rng() % mesh.vertices.size()] + 2 * h * double(rng() % 1000) / 1000 * dir3;
    if (!f.Inside(p)) continue;
    const double ref = BruteForceSignedDistance(mesh, p);
    EXPECT_NEAR(f.Distance(p), ref, std::sqrt(3.0) * h) << p.transpose();
  }
}

INSTANTIATE_TEST_SUITE_P(EveryClosedMesh, ClosedSharedMesh,
                         ::testing::Values("armadillo.obj", "dragon.obj", "bunny-watertight.obj", "bumpy-cube.obj",
                                           "knight.off", "screwdriver.off", "rocker-arm.obj", "fandisk.obj",
                                           "block.obj", "joint.obj", "spot.obj"),
                         TestName);

// A soup, a point well inside the object (as fractions of its bounding box), and the
// offset (metres, < 0: the default 1.5 voxels) that closes its holes.
struct SoupCase {
  std::string file;
  Eigen::Vector3d inside_fraction;
  double offset = -1;
};

class SoupSharedMesh : public ::testing::TestWithParam<SoupCase> {};

TEST_P(SoupSharedMesh, ZeroSetIsClosedAndFieldIsTheOffsetSurfaceDistance) {
  const std::filesystem::path path = testing::TestMesh(GetParam().file);
  const TriangleMesh mesh = LoadMesh(path);
  DistanceFieldOptions options = Quiet(48, FieldMode::kAuto);
  options.soup_offset = GetParam().offset;
  const DistanceField f = BuildDistanceField(mesh, options);
  ASSERT_EQ(f.info().mode, "soup");
  const double h = f.spacing(), offset = f.info().offset;
  // The zero set is closed: positive on the whole grid boundary, and marching cubes of the
  // final field (without closing at the boundary) has no boundary edges.
  EXPECT_GT(f.boundary_min(), 0);
  FieldGrid grid{f.origin(), f.spacing(), f.dims()};
  const TriangleMesh zero = ExtractIsosurface(f.values(), grid, 0.0);
  ASSERT_GT(zero.num_triangles(), 0);
  const auto census = testing::CountEdges(zero);
  EXPECT_EQ(census.boundary, 0);
  EXPECT_EQ(census.inconsistent, 0);
  // Well inside: about -(distance to the soup + offset).
  const Aabb box = mesh.Bounds();
  const Eigen::Vector3d inside = box.min + GetParam().inside_fraction.cwiseProduct(box.size());
  const double u_inside = BruteForceDistance(mesh, inside);
  ASSERT_GT(u_inside, 3 * h) << "the chosen inside point is too close to the soup";
  EXPECT_NEAR(f.Distance(inside), -(u_inside + offset), h);
  // Corners of the box are outside.
  const Aabb fbox = f.box();
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p((c & 1) ? fbox.max.x() : fbox.min.x(), (c & 2) ? fbox.max.y() : fbox.min.y(),
                            (c & 4) ? fbox.max.z() : fbox.min.z());
    EXPECT_GT(f.Distance(p), 0);
  }
  // Outside the offset surface the field is the soup distance minus the offset.
  std::mt19937 rng(43);
  int checked = 0;
  for (int s = 0; s < 300 && checked < 100; ++s) {
    const Eigen::Vector3d p = mesh.vertices[rng() % mesh.vertices.size()] + (offset + 4 * h) * Eigen::Vector3d::Random();
    if (!f.Inside(p) || f.Distance(p) < h) continue;
    ++checked;
    EXPECT_NEAR(f.Distance(p), BruteForceDistance(mesh, p) - offset, 0.5 * h) << p.transpose();
  }
  EXPECT_GT(checked, 30);
}

INSTANTIATE_TEST_SUITE_P(EverySoup, SoupSharedMesh,
                         ::testing::Values(// The scan's base has holes up to ~1.3 cm across: a 1.2 cm offset closes them.
                                           SoupCase{"stanford-bunny.obj", {0.5, 0.4, 0.5}, 0.012},
                                           SoupCase{"teapot.obj", {0.5, 0.5, 0.5}},
                                           SoupCase{"suzanne.obj", {0.5, 0.5, 0.5}}),
                         [](const ::testing::TestParamInfo<SoupCase>& info) {
                           std::string s = info.param.file.substr(0, info.param.file.find('.'));
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

}  // namespace
}  // namespace contactlab
