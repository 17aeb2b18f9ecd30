// The real meshes the repository ships (data/meshes/SOURCES.md) through LoadMesh and
// ValidateMesh: the closed ones must come out watertight, the open ones with their documented
// boundaries.
#include <gtest/gtest.h>

#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "test_support.h"

namespace contactlab {
namespace {

class ClosedSharedMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(ClosedSharedMesh, IsWatertightSingleComponentWithOutwardOrientation) {
  const std::string name = GetParam();
  const TriangleMesh mesh = LoadMesh(testing::TestMesh(name));
  const MeshReport r = ValidateMesh(mesh);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.nonmanifold_edges, 0);
  EXPECT_EQ(r.inconsistent_edges, 0);
  EXPECT_EQ(r.components, 1);
  EXPECT_TRUE(r.watertight) << r.ToText();
  EXPECT_GT(r.signed_volume, 0);
}

// Every mesh SOURCES.md lists as closed. block.obj has two pairs of coincident vertices whose
// welding collapses four triangles (reported as degenerate); the rest is watertight.
INSTANTIATE_TEST_SUITE_P(SharedMeshes, ClosedSharedMesh,
                         ::testing::Values("armadillo.obj", "dragon.obj", "bunny-watertight.obj", "bumpy-cube.obj",
                                           "knight.off", "screwdriver.off", "rocker-arm.obj", "fandisk.obj",
                                           "block.obj", "joint.obj", "spot.obj"));

TEST(SharedMeshes, TriangleCountsMatchSources) {
  const std::filesystem::path dragon = testing::TestMesh("dragon.obj");
  const TriangleMesh mesh = LoadMesh(dragon);
  EXPECT_EQ(mesh.num_triangles(), 100000);
  EXPECT_EQ(mesh.num_vertices(), 50000);
  const std::filesystem::path knight = testing::TestMesh("knight.off");
  EXPECT_EQ(LoadMesh(knight).num_triangles(), 1000);
}

TEST(SharedMeshes, BlockHasCoincidentVerticesButIsWatertight) {
  const std::filesystem::path block = testing::TestMesh("block.obj");
  const MeshReport r = ValidateMesh(LoadMesh(block));
  EXPECT_EQ(r.duplicate_vertices, 2);
  EXPECT_EQ(r.degenerate_triangles, 4);
  EXPECT_TRUE(r.watertight);
}

// The shipped scan is decimated to 15,925 triangles with its boundary edges kept (SOURCES.md).
TEST(SharedMeshes, StanfordBunnyHas223BoundaryEdges) {
  const std::filesystem::path bunny = testing::TestMesh("stanford-bunny.obj");
  const MeshReport r = ValidateMesh(LoadMesh(bunny));
  EXPECT_EQ(r.triangles, 15925);
  EXPECT_EQ(r.boundary_edges, 223);
  EXPECT_EQ(r.nonmanifold_edges, 0);
  EXPECT_FALSE(r.closed);
}

// SOURCES.md's 1,036 counts the triangles as indexed. The file repeats 403 vertices at
// exactly the same position; once they are welded, 160 boundary edges remain.
TEST(SharedMeshes, TeapotHas1036BoundaryEdgesAsIndexedAnd160Welded) {
  const std::filesystem::path teapot = testing::TestMesh("teapot.obj");
  const MeshReport r = ValidateMesh(LoadMesh(teapot));
  EXPECT_EQ(r.triangles, 6320);
  EXPECT_EQ(r.unwelded_boundary_edges, 1036);
  EXPECT_EQ(r.duplicate_vertices, 403);
  EXPECT_EQ(r.boundary_edges, 160);
  EXPECT_FALSE(r.closed);
}

// Suzanne: 500 faces (468 quads, 32 triangles) triangulated to 968 triangles. Two vertices
// repeat exact positions; welding them makes one edge non-manifold and one triangle a duplicate.
TEST(SharedMeshes, SuzanneHas42BoundaryEdgesAndTriangulatedQuads) {
  const std::filesystem::path suzanne = testing::TestMesh("suzanne.obj");
  const MeshReport r = ValidateMesh(LoadMesh(suzanne));
  EXPECT_EQ(r.triangles, 468 * 2 + 32);
  EXPECT_EQ(r.boundary_edges, 42);
  EXPECT_EQ(r.unwelded_boundary_edges, 42);
  EXPECT_EQ(r.duplicate_vertices, 2);
  EXPECT_EQ(r.nonmanifold_edges, 1);
  EXPECT_EQ(r.duplicate_triangles, 1);
  EXPECT_FALSE(r.closed);
}

}  // namespace
}  // namespace contactlab
