// Mesh validation (geometry/mesh_validation.h): counts on procedural shapes whose topology is
// known by construction, and on the same shapes broken in one known way.
#include "geometry/mesh_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "geometry/procedural_shapes.h"
#include "util/error.h"

namespace contactlab {
namespace {

const Eigen::Vector3d kHalf(1.0 / 3.0, 0.5, 0.7);

TEST(ValidateMesh, ProceduralShapesAreWatertightSingleComponents) {
  const TriangleMesh shapes[] = {MakeSphere(0.3, 2), MakeBox(kHalf), MakeBox(kHalf, 3), MakeTorus(1, 0.25, 24, 12),
                                 MakeCapsule(0.2, 0.5, 16, 4), MakeBumpyPlate(1, 0.1, 3, 0.05, 24)};
  for (const TriangleMesh& mesh : shapes) {
    SCOPED_TRACE(mesh.name);
    const MeshReport r = ValidateMesh(mesh);
    EXPECT_EQ(r.vertices, mesh.num_vertices());
    EXPECT_EQ(r.triangles, mesh.num_triangles());
    EXPECT_EQ(r.boundary_edges, 0);
    EXPECT_EQ(r.nonmanifold_edges, 0);
    EXPECT_EQ(r.inconsistent_edges, 0);
    EXPECT_EQ(r.degenerate_triangles, 0);
    EXPECT_EQ(r.duplicate_triangles, 0);
    EXPECT_EQ(r.components, 1);
    EXPECT_TRUE(r.closed);
    EXPECT_TRUE(r.consistently_oriented);
    EXPECT_TRUE(r.watertight);
    EXPECT_GT(r.signed_volume, 0);  // outward orientation
    EXPECT_EQ(3 * r.triangles, 2 * r.edges);  // closed 2-manifold: each edge has two sides
  }
}

TEST(ValidateMesh, BoxMeasuresAreExact) {
  const MeshReport r = ValidateMesh(MakeBox(kHalf));
  EXPECT_NEAR(r.signed_volume, 8 * kHalf.prod(), 1e-15);
  EXPECT_NEAR(r.surface_area, 8 * (kHalf.x() * kHalf.y() + kHalf.y() * kHalf.z() + kHalf.z() * kHalf.x()), 1e-15);
  EXPECT_EQ(r.bounds.min, -kHalf);
  EXPECT_EQ(r.bounds.max, kHalf);
  EXPECT_EQ(r.edges, 18);
}

TEST(ValidateMesh, BoxWithOneTriangleRemovedHasThreeBoundaryEdges) {
  TriangleMesh box = MakeBox(kHalf);
  box.triangles.erase(box.triangles.begin() + 5);
  const MeshReport r = ValidateMesh(box);
  EXPECT_EQ(r.boundary_edges, 3);
  EXPECT_EQ(r.nonmanifold_edges, 0);
  EXPECT_EQ(r.inconsistent_edges, 0);
  EXPECT_FALSE(r.closed);
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_FALSE(r.watertight);
}

TEST(ValidateMesh, BoxWithOneTriangleFlippedHasThreeInconsistentEdges) {
  TriangleMesh box = MakeBox(kHalf);
  std::swap(box.triangles[7][0], box.triangles[7][1]);
  const MeshReport r = ValidateMesh(box);
  EXPECT_EQ(r.inconsistent_edges, 3);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_TRUE(r.closed);
  EXPECT_FALSE(r.consistently_oriented);
  EXPECT_FALSE(r.watertight);
}

TEST(ValidateMesh, TwoBoxesGluedAlongAnEdgeHaveANonManifoldEdge) {
  // The second box touches the first along the edge y = z = half, x in [-half, half].
  TriangleMesh boxes = MakeBox(kHalf);
  TriangleMesh second = MakeBox(kHalf);
  second.Transform(1, Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 2 * kHalf.y(), 2 * kHalf.z()));
  boxes.Append(second);
  const MeshReport r = ValidateMesh(boxes);
  EXPECT_EQ(r.duplicate_vertices, 2);  // the glued edge's two end points
  EXPECT_EQ(r.nonmanifold_edges, 1);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.inconsistent_edges, 0);
  EXPECT_EQ(r.components, 1);  // joined through the welded vertices
  EXPECT_FALSE(r.closed);
  EXPECT_FALSE(r.watertight);
}

TEST(ValidateMesh, SeparateShapesAreSeparateComponents) {
  TriangleMesh two = MakeSphere(0.3, 1);
  TriangleMesh other = MakeBox(kHalf);
  other.Transform(1, Eigen::Matrix3d::Identity(), Eigen::Vector3d(5, 0, 0));
  two.Append(other);
  const MeshReport r = ValidateMesh(two);
  EXPECT_EQ(r.components, 2);
  EXPECT_TRUE(r.watertight);
}

TEST(ValidateMesh, SoupWithVerticesRepeatedPerFaceIsWeldedBeforeEdgeAnalysis) {
  const TriangleMesh box = MakeBox(kHalf);
  TriangleMesh soup;
  for (const Eigen::Vector3i& t : box.triangles) {
    const int base = soup.num_vertices();
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(box.vertices[t[k]]);
    soup.triangles.emplace_back(base, base + 1, base + 2);
  }
  const MeshReport r = ValidateMesh(soup);
  EXPECT_EQ(r.vertices, 36);
  EXPECT_EQ(r.duplicate_vertices, 36 - 8);
  EXPECT_EQ(r.unwelded_boundary_edges, 36);
  EXPECT_EQ(r.boundary_edges, 0);
  EXPECT_EQ(r.edges, 18);
  EXPECT_TRUE(r.watertight);
  EXPECT_NEAR(r.signed_volume, 8 * kHalf.prod(), 1e-15);
}

TEST(ValidateMesh, CountsUnreferencedDegenerateAndDuplicateTriangles) {
  TriangleMesh mesh = MakeBox(kHalf);
  const int n = mesh.num_vertices();
  mesh.vertices.push_back(Eigen::Vector3d(9, 9, 9));            // unreferenced
  mesh.vertices.push_back(Eigen::Vector3d(-kHalf.x(), 0, 0));    // for a zero-area triangle
  mesh.vertices.push_back(Eigen::Vector3d(kHalf.x(), 0, 0));
  const Eigen::Vector3i first = mesh.triangles[0];
  mesh.triangles.push_back(Eigen::Vector3i(first[1], first[2], first[0]));  // duplicate, rotated
  mesh.triangles.push_back(Eigen::Vector3i(0, 0, 1));                       // repeated index
  mesh.triangles.push_back(Eigen::Vector3i(n + 1, n + 2, n + 1));           // repeated index
  mesh.triangles.push_back(Eigen::Vector3i(n + 1, n + 2, n + 1));           // and duplicate
  const MeshReport r = ValidateMesh(mesh);
  EXPECT_EQ(r.unreferenced_vertices, 1);
  EXPECT_EQ(r.degenerate_triangles, 3);
  EXPECT_EQ(r.duplicate_triangles, 2);
  EXPECT_EQ(r.nonmanifold_edges, 3);  // the duplicated box triangle's edges now have 3 uses
}

TEST(ValidateMesh, ZeroAreaTriangleWithDistinctVerticesIsDegenerate) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1.0 / 3.0, 0, 0}, {1, 0, 0}};
  mesh.triangles = {{0, 1, 2}};
  EXPECT_EQ(ValidateMesh(mesh).degenerate_triangles, 1);
  mesh.vertices[1].y() = 1e-3;  // thin but not degenerate
  EXPECT_EQ(ValidateMesh(mesh).degenerate_triangles, 0);
}

TEST(ValidateMesh, ThrowsOnIndexOutOfRangeOrNonFiniteVertex) {
  TriangleMesh mesh = MakeBox(kHalf);
  mesh.triangles.push_back(Eigen::Vector3i(0, 1, 8));
  EXPECT_THROW(ValidateMesh(mesh), Error);
  mesh = MakeBox(kHalf);
  mesh.vertices[3].x() = std::nan("");
  EXPECT_THROW(ValidateMesh(mesh), Error);
}

TEST(MeshReport, TextAndJsonCarryTheCounts) {
  TriangleMesh box = MakeBox(kHalf);
  box.triangles.pop_back();
  const MeshReport r = ValidateMesh(box);
  const nlohmann::json j = nlohmann::json::parse(r.ToJson());
  EXPECT_EQ(j.at("triangles").get<int>(), 11);
  EXPECT_EQ(j.at("boundary_edges").get<int>(), 3);
  EXPECT_FALSE(j.at("watertight").get<bool>());
  EXPECT_DOUBLE_EQ(j.at("surface_area").get<double>(), r.surface_area);
  EXPECT_DOUBLE_EQ(j.at("bounds").at("max")[2].get<double>(), kHalf.z());
  const std::string text = r.ToText();
  EXPECT_NE(text.find("boundary edges:          3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("watertight:              no\n"), std::string::npos) << text;
}

}  // namespace
}  // namespace contactlab
