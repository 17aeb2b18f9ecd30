// The BVH + pseudo-normal signed distance (the deformed-field study's exact reference) against
// brute force: distance to every triangle and the winding-number sign, on procedural meshes, a
// twisted (deformed) box and the armadillo, at points near and far from the surface.
#include "sdf/mesh_signed_distance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "geometry/mesh_io.h"
#include "geometry/procedural_shapes.h"
#include "sdf_reference.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Random points in MESH's bounding box grown by 20%, half of them pulled to within a few
// percent of the size from the surface (vertices and edge midpoints, jittered), where the
// sign is hardest.
std::vector<Eigen::Vector3d> TestPoints(const TriangleMesh& mesh, int count, std::mt19937* rng) {
  const Aabb b = mesh.Bounds();
  const Eigen::Vector3d lo = b.min - 0.2 * b.size(), size = 1.4 * b.size();
  std::uniform_real_distribution<double> u(0, 1), j(-1, 1);
  const double s = 0.03 * b.size().maxCoeff();
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < count; ++i) {
    if (i % 2 == 0) {
      out.push_back(lo + size.cwiseProduct(Eigen::Vector3d(u(*rng), u(*rng), u(*rng))));
    } else {
      const Eigen::Vector3i& t = mesh.triangles[(*rng)() % mesh.triangles.size()];
      const Eigen::Vector3d base =
          i % 4 == 1 ? mesh.vertices[t[0]] : 0.5 * (mesh.vertices[t[0]] + mesh.vertices[t[1]]);
      out.push_back(base + s * Eigen::Vector3d(j(*rng), j(*rng), j(*rng)));
    }
  }
  return out;
}

void ExpectMatchesBruteForce(const TriangleMesh& mesh, int count) {
  const MeshSignedDistance d(mesh, "test");
  std::mt19937 rng(17);
  const double tol = 1e-9 * mesh.Bounds().size().maxCoeff();
  int inside = 0;
  for (const Eigen::Vector3d& p : TestPoints(mesh, count, &rng)) {
    const double ref = testing::BruteForceSignedDistance(mesh, p);
    Eigen::Vector3d c;
    const double v = d.Distance(p, &c);
    EXPECT_NEAR(std::abs(v), std::abs(ref), tol) << mesh.name << " at " << p.transpose();
    EXPECT_NEAR((p - c).norm(), std::abs(ref), tol) << mesh.name;
    if (std::abs(ref) > tol) {
      EXPECT_EQ(v < 0, ref < 0) << mesh.name << " at " << p.format(Eigen::IOFormat(17)) << ": " << v << " vs " << ref;
    }
    inside += ref < 0;
  }
  EXPECT_GT(inside, count / 20) << mesh.name << ": the points reach inside";
}

TEST(MeshSignedDistance, MatchesBruteForceOnProceduralMeshes) {
  ExpectMatchesBruteForce(MakeSphere(0.3, 3), 600);
  ExpectMatchesBruteForce(MakeBox(Eigen::Vector3d(0.1, 1.0 / 3, 0.02), 3), 600);  // a slab
  ExpectMatchesBruteForce(MakeTorus(0.15, 0.04, 32, 12), 600);
}

TEST(MeshSignedDistance, MatchesBruteForceOnATwistedBox) {
  // A bar twisted by 90 degrees along its length: curved, non-convex, as a deformed mesh is.
  TriangleMesh bar = MakeBox(Eigen::Vector3d(0.05, 0.02, 0.3), 8);
  for (Eigen::Vector3d& v : bar.vertices) {
    v = Eigen::AngleAxisd(M_PI / 2 * (v.z() + 0.3) / 0.6, Eigen::Vector3d::UnitZ()) * v;
  }
  ExpectMatchesBruteForce(bar, 600);
}

TEST(MeshSignedDistance, MatchesBruteForceOnTheArmadillo) {
  ExpectMatchesBruteForce(LoadMesh(testing::TestMesh("armadillo.obj")), 200);
}

TEST(MeshSignedDistance, RefusesOpenOrInconsistentMeshes) {
  TriangleMesh open = MakeBox(Eigen::Vector3d(0.1, 0.1, 0.1), 2);
  open.triangles.pop_back();
  EXPECT_THROW(MeshSignedDistance(open, "open box"), Error);
  TriangleMesh flipped = MakeBox(Eigen::Vector3d(0.1, 0.1, 0.1), 2);
  std::swap(flipped.triangles[0][0], flipped.triangles[0][1]);
  EXPECT_THROW(MeshSignedDistance(flipped, "flipped box"), Error);
  EXPECT_THROW(MeshSignedDistance(TriangleMesh{}, "empty"), Error);
}

}  // namespace
}  // namespace contactlab
