#include "deform/tet_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <map>

#include "deform/anchoring.h"
#include "deform/embedded_points.h"
#include "beam_fixture.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Samples the sphere's exact signed distance on a grid covering [-L, L]^3.
DistanceField SampledSphere(double radius, double half_extent, int n) {
  const double h = 2 * half_extent / (n - 1);
  const Eigen::Vector3d origin = Eigen::Vector3d::Constant(-half_extent);
  std::vector<float> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(float((origin + h * Eigen::Vector3d(i, j, k)).norm() - radius));
  return DistanceField(origin, h, Eigen::Vector3i::Constant(n), std::move(v), {"sphere", "analytic", 0, 0});
}

// Triangle faces used once (boundary) and the largest use count of any face.
std::pair<double, int> BoundaryAreaAndMaxUse(const TetMesh& mesh) {
  std::map<std::array<int, 3>, int> uses;
  for (const auto& t : mesh.tets) {
    const int f[4][3] = {{t[1], t[2], t[3]}, {t[0], t[2], t[3]}, {t[0], t[1], t[3]}, {t[0], t[1], t[2]}};
    for (const auto& face : f) {
      std::array<int, 3> key = {face[0], face[1], face[2]};
      std::sort(key.begin(), key.end());
      ++uses[key];
    }
  }
  double area = 0;
  int max_use = 0;
  for (const auto& [key, n] : uses) {
    max_use = std::max(max_use, n);
    if (n == 1) {
      area += 0.5 * (mesh.vertices[key[1]] - mesh.vertices[key[0]]).cross(mesh.vertices[key[2]] - mesh.vertices[key[0]]).norm();
    }
  }
  return {area, max_use};
}

TEST(TetMesh, BoxSplitsAreConformingAndFillTheBox) {
  for (TetSplit split : {TetSplit::kFive, TetSplit::kSix}) {
    const TetMesh mesh = MakeBoxTetMesh(Eigen::Vector3d(-0.5, 0, 0), Eigen::Vector3d(0.5, 1.0 / 3, 2.0 / 3), 3, 1, 2, split);
    EXPECT_EQ(mesh.num_tets(), 6 * (split == TetSplit::kSix ? 6 : 5));
    for (int t = 0; t < mesh.num_tets(); ++t) EXPECT_GT(mesh.TetVolume(t), 0);
    EXPECT_NEAR(mesh.Volume(), 1.0 * (1.0 / 3) * (2.0 / 3), 1e-14);
    // A conforming mesh uses every interior face twice, and its boundary is the box surface.
    const auto [area, max_use] = BoundaryAreaAndMaxUse(mesh);
    EXPECT_EQ(max_use, 2);
    EXPECT_NEAR(area, 2 * (1.0 / 3 + 2.0 / 3 + 2.0 / 9), 1e-12);
  }
}

TEST(TetMesh, VoxelisedSphereCoversTheSurfaceAndIsConforming) {
  const double R = 0.3;
  const DistanceField field = SampledSphere(R, 0.5, 41);
  VoxelMeshOptions options;
  options.cells = 8;
  const TetMesh mesh = BuildVoxelTetMesh(field, options);
  EXPECT_EQ(BoundaryAreaAndMaxUse(mesh).second, 2);
  const double sphere = 4.0 / 3 * M_PI * R * R * R;
  EXPECT_GT(mesh.Volume(), sphere);
  EXPECT_LT(mesh.Volume(), 3 * sphere);
  // Points of the sphere's surface lie inside the mesh.
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  for (int s = 0; s < 200; ++s) {
    const Eigen::Vector3d p = R * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    Eigen::Vector4d b;
    LocateInTetMesh(mesh, p, &b);
    EXPECT_GE(b.minCoeff(), -1e-9) << p.transpose();
  }
}

TEST(TetMesh, LargestComponentDropsTheSmallerBlob) {
  // Two spheres: radius 0.25 at x = -0.2 and radius 0.1 at x = +0.35.
  const int n = 41;
  const double L = 0.5, h = 2 * L / (n - 1);
  std::vector<float> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d p = Eigen::Vector3d::Constant(-L) + h * Eigen::Vector3d(i, j, k);
        v.push_back(float(std::min((p - Eigen::Vector3d(-0.2, 0, 0)).norm() - 0.25, (p - Eigen::Vector3d(0.37, 0, 0)).norm() - 0.1)));
      }
  const DistanceField field(Eigen::Vector3d::Constant(-L), h, Eigen::Vector3i::Constant(n), v, {"two spheres", "analytic", 0, 0});
  VoxelMeshOptions options;
  options.cells = 12;
  options.threshold = 0.5;
  const TetMesh one = BuildVoxelTetMesh(field, options);
  options.largest_component = false;
  const TetMesh all = BuildVoxelTetMesh(field, options);
  EXPECT_LT(one.num_tets(), all.num_tets());
  EXPECT_LT(one.Bounds().max.x(), 0.2);
  EXPECT_GT(all.Bounds().max.x(), 0.3);
}

TEST(TetMesh, FieldWithoutInteriorIsRejected) {
  std::vector<float> v(27, 1.f);
  const DistanceField field(Eigen::Vector3d::Zero(), 0.1, Eigen::Vector3i(3, 3, 3), v, {"empty", "analytic", 0, 0});
  EXPECT_THROW(BuildVoxelTetMesh(field), Error);
  VoxelMeshOptions bad;
  bad.cells = 0;
  EXPECT_THROW(BuildVoxelTetMesh(SampledSphere(0.3, 0.5, 9), bad), Error);
}

TEST(Anchoring, FixesVerticesBelowPlaneAndInBoxAndRejectsEmptySets) {
  const TetMesh mesh = testing::MakeBeam();
  const auto below = FindFixedVertices(mesh, Anchoring::BelowPlane(Eigen::Vector3d::UnitX(), 1e-9));
  EXPECT_EQ(std::count(below.begin(), below.end(), 1), 4 * 4);
  Aabb box;
  box.min = Eigen::Vector3d(0.9, -1, -1);
  box.max = Eigen::Vector3d(2, 2, 2);
  const auto in_box = FindFixedVertices(mesh, Anchoring::InBox(box));
  EXPECT_EQ(std::count(in_box.begin(), in_box.end(), 1), 2 * 4 * 4);
  // Outside a box spanning the middle: both ends fixed, as for a bridge.
  Aabb span;
  span.min = Eigen::Vector3d(0.01, -1, -1);
  span.max = Eigen::Vector3d(0.9, 2, 2);
  const auto ends = FindFixedVertices(mesh, Anchoring::OutsideBox(span));
  const auto middle = FindFixedVertices(mesh, Anchoring::InBox(span));
  for (std::size_t v = 0; v < ends.size(); ++v) {
    EXPECT_NE(ends[v], middle[v]);
    const double x = mesh.vertices[v].x();
    EXPECT_EQ(ends[v], (x < 0.01 || x > 0.9) ? 1 : 0);
  }
  EXPECT_THROW(FindFixedVertices(mesh, Anchoring::BelowY(-0.1)), Error);
  EXPECT_THROW(FindFixedVertices(mesh, Anchoring::BelowY(10)), Error);
  const auto none = FindFixedVertices(mesh, Anchoring::Free());
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
}

}  // namespace
}  // namespace contactlab
