// MeshFromArrays (geometry/mesh_from_arrays.h): another tool's arrays become the mesh the file
// readers would give, and what a reader refuses is refused with its message and the row.
#include "geometry/mesh_from_arrays.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/mesh_io.h"
#include "test_support.h"

namespace contactlab {
namespace {

// A tetrahedron with edges of 1/3 m (not exact in binary), outward counter-clockwise.
const std::vector<double> kVertices = {0, 0, 0, 1.0 / 3, 0, 0, 0, 1.0 / 3, 0, 0, 0, 1.0 / 3};
const std::vector<std::int64_t> kTriangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

std::string ErrorFrom(std::vector<double> v, std::vector<std::int64_t> t) {
  return testing::ErrorOf([&] { MeshFromArrays(v, t, "tet", "Mesh 'tet'"); });
}

TEST(MeshFromArrays, EqualsTheSameMeshReadFromAnObjFile) {
  const TriangleMesh m = MeshFromArrays(kVertices, kTriangles, "tet", "Mesh 'tet'");
  testing::TempDir dir;
  SaveMesh(m, dir / "tet.obj");
  const TriangleMesh read = LoadMesh(dir / "tet.obj");
  EXPECT_EQ(m.name, "tet");
  ASSERT_EQ(m.vertices.size(), read.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) EXPECT_EQ(m.vertices[i], read.vertices[i]) << i;
  EXPECT_EQ(m.triangles, read.triangles);
  EXPECT_NEAR(m.SignedVolume(), 1.0 / 162, 1e-15);  // (1/3)^3 / 6
}

TEST(MeshFromArrays, RefusesWhatTheReadersRefuseNamingTheRow) {
  std::vector<double> v = kVertices;
  v[7] = std::nan("");
  EXPECT_EQ(ErrorFrom(v, kTriangles), "Mesh 'tet': vertex 2 is not finite: (0, nan, 0)");
  v[7] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ErrorFrom(v, kTriangles), "Mesh 'tet': vertex 2 is not finite: (0, inf, 0)");
  v[7] = 2e9;
  EXPECT_EQ(ErrorFrom(v, kTriangles),
            "Mesh 'tet': vertex 2: coordinates out of range: |coordinate| reaches 2e+09 m (the limit is 1e+09 m)");
  std::vector<std::int64_t> t = kTriangles;
  t[7] = 4;
  EXPECT_EQ(ErrorFrom(kVertices, t), "Mesh 'tet': triangle 2: face vertex index 4 out of range [0, 4)");
  t[7] = -1;
  EXPECT_EQ(ErrorFrom(kVertices, t), "Mesh 'tet': triangle 2: face vertex index -1 out of range [0, 4)");
  t[7] = std::int64_t(1) << 33;  // beyond int: refused before it narrows
  EXPECT_EQ(ErrorFrom(kVertices, t), "Mesh 'tet': triangle 2: face vertex index 8589934592 out of range [0, 4)");
  EXPECT_EQ(ErrorFrom(kVertices, {}), "Mesh 'tet': no faces: the mesh has no triangles");
  EXPECT_EQ(ErrorFrom({}, kTriangles), "Mesh 'tet': triangle 0: face vertex index 0 out of range [0, 0)");
  EXPECT_EQ(ErrorFrom({0, 0}, kTriangles), "Mesh 'tet': vertices hold 2 numbers, not rows of 3 (x, y, z)");
  EXPECT_EQ(ErrorFrom(kVertices, {0, 1}), "Mesh 'tet': triangles hold 2 indices, not rows of 3");
}

TEST(MeshFromArrays, AcceptsPolygonSoupsAsTheReadersDo) {
  // A degenerate triangle (repeated index) and an unreferenced vertex: a soup, not an error.
  const std::vector<double> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5};
  const std::vector<std::int64_t> t = {0, 1, 2, 0, 0, 1};
  const TriangleMesh m = MeshFromArrays(v, t, "soup", "soup");
  EXPECT_EQ(m.num_triangles(), 2);
  EXPECT_EQ(m.num_vertices(), 4);
}

TEST(CheckMeshContent, RefusesAMeshBuiltInMemoryThatNoReaderWouldReturn) {
  TriangleMesh m = MeshFromArrays(kVertices, kTriangles, "tet", "tet");
  EXPECT_NO_THROW(CheckMeshContent(m, "tet"));
  m.triangles[1][2] = 9;
  EXPECT_EQ(testing::ErrorOf([&] { CheckMeshContent(m, "tet"); }),
            "tet: triangle 1: face vertex index 9 out of range [0, 4)");
  m.triangles.clear();
  EXPECT_EQ(testing::ErrorOf([&] { CheckMeshContent(m, "tet"); }), "tet: no faces: the mesh has no triangles");
}

}  // namespace
}  // namespace contactlab
