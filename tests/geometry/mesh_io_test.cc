// Mesh readers and writers (geometry/mesh_io.h): each format parsed from small hand-written
// files, round trips through every writer, and the load-time scale and pose.
#include "geometry/mesh_io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>

#include "geometry/mesh_test_util.h"
#include "geometry/mesh_validation.h"
#include "geometry/procedural_shapes.h"
#include "test_support.h"

namespace contactlab {
namespace {

using testing::ByteBuilder;
using testing::TempDir;
using testing::WriteFixture;

// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) as outward facets, one row per
// facet; volume 1/6.
const double kTetraFacets[4][3][3] = {
    {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}},
    {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}},
    {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
};

std::string TetraBinaryStl(const std::string& header_text) {
  std::string header = header_text;
  header.resize(80, ' ');
  ByteBuilder b;
  b.Text(header).Put<std::uint32_t>(4);
  for (const auto& facet : kTetraFacets) {
    for (int a = 0; a < 3; ++a) b.Put<float>(0);  // normal: ignored by the reader
    for (const auto& p : facet) {
      for (int a = 0; a < 3; ++a) b.Put<float>(static_cast<float>(p[a]));
    }
    b.Put<std::uint16_t>(0);
  }
  return b.bytes();
}

void ExpectUnitTetrahedron(const TriangleMesh& mesh) {
  EXPECT_EQ(mesh.num_vertices(), 4);  // welded from 12 facet corners
  EXPECT_EQ(mesh.num_triangles(), 4);
  const MeshReport report = ValidateMesh(mesh);
  EXPECT_TRUE(report.watertight);
  EXPECT_DOUBLE_EQ(report.signed_volume, 1.0 / 6.0);
}

TEST(ObjReader, ParsesQuadsSlashFormsNegativeIndicesAndIgnoresOtherRecords) {
  TempDir dir;
  const auto path = WriteFixture(dir / "square.obj",
                                 "# a unit square as a quad, then faces with other index forms\n"
                                 "mtllib x.mtl\no thing\n"
                                 "v 0 0 0\nv 1 0 0\r\nv 1 1 0\n"
                                 "v 0 1 0   # trailing comment\n"
                                 "vt 0 0\nvn 0 0 1\ng group\nusemtl m\ns off\n"
                                 "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
                                 "v +0.5 0.5 1e0 1.0\n"
                                 "f -4//1 -3//1 -1//1\n"
                                 "f 1/1 2/1 5/1\n"
                                 "l 1 2\n\n");
  const TriangleMesh mesh = LoadMesh(path);
  ASSERT_EQ(mesh.num_vertices(), 5);
  EXPECT_EQ(mesh.vertices[4], Eigen::Vector3d(0.5, 0.5, 1.0));
  ASSERT_EQ(mesh.num_triangles(), 4);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));  // quad fan
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(1, 2, 4));  // -4 -3 -1 of 5 vertices
  EXPECT_EQ(mesh.triangles[3], Eigen::Vector3i(0, 1, 4));
  EXPECT_EQ(mesh.name, "square.obj");
}

TEST(ObjReader, PentagonIsFanTriangulated) {
  TempDir dir;
  const auto path = WriteFixture(dir / "pentagon.OBJ",  // extension is case-insensitive
                                 "v 1 0 0\nv 0.3 0.95 0\nv -0.8 0.6 0\nv -0.8 -0.6 0\nv 0.3 -0.95 0\nf 1 2 3 4 5\n");
  const TriangleMesh mesh = LoadMesh(path);
  ASSERT_EQ(mesh.num_triangles(), 3);
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(0, 3, 4));
}

TEST(OffReader, ParsesCommentsColoursAndPolygons) {
  TempDir dir;
  const auto path = WriteFixture(dir / "tet.off",
                                 "# comment before the header\n"
                                 "COFF\n"
                                 "# counts\n"
                                 "4 3 0\n"
                                 "\n"
                                 "0 0 0 255 0 0 255\n"
                                 "1 0 0 255 0 0 255\n"
                                 "0 1 0 0 255 0 255\n"
                                 "0 0 1 0 0 255 255\n"
                                 "3 0 2 1  255 0 0\n"
                                 "4 0 1 3 2\n"
                                 "3 1 2 3 # trailing comment\n");
  const TriangleMesh mesh = LoadMesh(path);
  ASSERT_EQ(mesh.num_vertices(), 4);
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 0, 1));
  ASSERT_EQ(mesh.num_triangles(), 4);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 2, 1));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 1, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(0, 3, 2));
  EXPECT_EQ(mesh.triangles[3], Eigen::Vector3i(1, 2, 3));
}

TEST(OffReader, AcceptsCountsOnTheHeaderLine) {
  TempDir dir;
  const auto path = WriteFixture(dir / "tri.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const TriangleMesh mesh = LoadMesh(path);
  EXPECT_EQ(mesh.num_vertices(), 3);
  EXPECT_EQ(mesh.num_triangles(), 1);
}

TEST(StlReader, AsciiFacetsAreWeldedIntoSharedVertices) {
  std::string text = "solid tet\n";
  for (const auto& facet : kTetraFacets) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (const auto& p : facet) {
      text += "      vertex " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  text += "endsolid tet\n";
  TempDir dir;
  ExpectUnitTetrahedron(LoadMesh(WriteFixture(dir / "tet.stl", text)));
}

TEST(StlReader, BinaryWithSolidHeaderIsReadAsBinary) {
  TempDir dir;
  ExpectUnitTetrahedron(LoadMesh(WriteFixture(dir / "tet.stl", TetraBinaryStl("solid but binary"))));
  ExpectUnitTetrahedron(LoadMesh(WriteFixture(dir / "tet2.stl", TetraBinaryStl("exported by some tool"))));
}

TEST(PlyReader, AsciiSkipsOtherPropertiesListsAndElements) {
  TempDir dir;
  const auto path = WriteFixture(dir / "square.ply",
                                 "ply\n"
                                 "format ascii 1.0\n"
                                 "comment made by hand\n"
                                 "element vertex 4\n"
                                 "property float x\n"
                                 "property uchar red\n"
                                 "property float y\n"
                                 "property float z\n"
                                 "property list uchar float dummy_list\n"
                                 "element edge 1\n"
                                 "property int vertex1\n"
                                 "property int vertex2\n"
                                 "element face 2\n"
                                 "property list uchar int vertex_indices\n"
                                 "property list uchar float texcoord\n"
                                 "property int flags\n"
                                 "end_header\n"
                                 "0 9 0 0 2 0.5 0.5\n"
                                 "1 9 0 0 0\n"
                                 "1 9 1 0 1 7\n"
                                 "0 9 1 0.25 0\n"
                                 "0 1\n"
                                 "4 0 1 2 3 6 0 0 1 0 1 1 5\n"
                                 "3 0 2 1 0 7\n");
  const TriangleMesh mesh = LoadMesh(path);
  ASSERT_EQ(mesh.num_vertices(), 4);
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 1, 0.25));
  ASSERT_EQ(mesh.num_triangles(), 3);
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(0, 2, 1));
}

TEST(PlyReader, BinaryBigEndianWithDoublesIntCountsAndExtraLists) {
  ByteBuilder b(/*big_endian=*/true);
  b.Text(
      "ply\nformat binary_big_endian 1.0\n"
      "element vertex 3\nproperty double x\nproperty double y\nproperty double z\nproperty float confidence\n"
      "element face 2\nproperty list int uint vertex_index\nproperty list uchar uchar extra\n"
      "end_header\n");
  const Eigen::Vector3d p[3] = {{1.0 / 3, 2, -1.5}, {4, 5, 6}, {7, 8, 9.25}};
  for (const auto& v : p) b.Put<double>(v.x()).Put<double>(v.y()).Put<double>(v.z()).Put<float>(0.5f);
  b.Put<std::int32_t>(3).Put<std::uint32_t>(2).Put<std::uint32_t>(0).Put<std::uint32_t>(1);
  b.Put<std::uint8_t>(2).Put<std::uint8_t>(11).Put<std::uint8_t>(12);
  b.Put<std::int32_t>(3).Put<std::uint32_t>(0).Put<std::uint32_t>(1).Put<std::uint32_t>(2);
  b.Put<std::uint8_t>(0);
  TempDir dir;
  const TriangleMesh mesh = LoadMesh(WriteFixture(dir / "be.ply", b.bytes()));
  ASSERT_EQ(mesh.num_vertices(), 3);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(mesh.vertices[i], p[i]);
  ASSERT_EQ(mesh.num_triangles(), 2);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(2, 0, 1));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 1, 2));
}

TEST(PlyReader, BinaryLittleEndianFloatsWithTrailingElement) {
  ByteBuilder b;
  b.Text(
      "ply\nformat binary_little_endian 1.0\n"
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
      "element material 1\nproperty list ushort short coefficients\n"
      "end_header\n");
  const float p[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.5f}};
  for (const auto& v : p) b.Put<float>(v[0]).Put<float>(v[1]).Put<float>(v[2]);
  b.Put<std::uint8_t>(7).Put<std::uint8_t>(4).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2).Put<std::int32_t>(3);
  b.Put<std::uint16_t>(2).Put<std::int16_t>(-1).Put<std::int16_t>(1);
  TempDir dir;
  const TriangleMesh mesh = LoadMesh(WriteFixture(dir / "le.ply", b.bytes()));
  ASSERT_EQ(mesh.num_vertices(), 4);
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 1, 0.5));
  ASSERT_EQ(mesh.num_triangles(), 2);
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
}

// V rounded to the nearest float (volatile: GCC 12 -O3 was seen to drop the rounding here).
double RoundToFloat(double v) {
  volatile float rounded = static_cast<float>(v);
  return rounded;
}

// Sizes that are not exact in binary, so a lossy writer would show.
TriangleMesh RoundTripSubject() { return MakeTorus(1.0 / 3.0, 0.1, 12, 8); }

class ExactRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(ExactRoundTrip, SaveThenLoadGivesTheSameMesh) {
  const TriangleMesh mesh = RoundTripSubject();
  TempDir dir;
  const auto path = dir / (std::string("torus.") + GetParam());
  SaveMesh(mesh, path);
  const TriangleMesh loaded = LoadMesh(path);
  ASSERT_EQ(loaded.num_vertices(), mesh.num_vertices());
  ASSERT_EQ(loaded.num_triangles(), mesh.num_triangles());
  for (int i = 0; i < mesh.num_vertices(); ++i) EXPECT_EQ(loaded.vertices[i], mesh.vertices[i]) << i;
  for (int t = 0; t < mesh.num_triangles(); ++t) EXPECT_EQ(loaded.triangles[t], mesh.triangles[t]) << t;
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
}

INSTANTIATE_TEST_SUITE_P(MeshIo, ExactRoundTrip, ::testing::Values("obj", "off", "ply"));

// A vertex that is not finite (a deformation that overflowed) is refused in every format, naming
// the file and the vertex, and nothing is written.
TEST(MeshWriter, ANonFiniteVertexIsRefusedAndNothingWritten) {
  TriangleMesh mesh = RoundTripSubject();
  mesh.vertices[5].y() = std::numeric_limits<double>::infinity();
  TempDir dir;
  for (const char* ext : {"obj", "off", "ply", "stl"}) {
    const auto path = dir / (std::string("bad.") + ext);
    try {
      SaveMesh(mesh, path);
      ADD_FAILURE() << "no error for " << ext;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path.string() + ": cannot save: vertex 5 has a non-finite coordinate", 0), 0u) << msg;
    }
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

// A finite vertex beyond kMaxCoordinate (body-export of a body deformed by q = 1e30 wrote one
// at 5.6e30 m) is refused in every format, as LoadMesh would refuse it; nothing is written. A mesh
// at the limit itself round-trips.
TEST(MeshWriter, AVertexTheReadersWouldRefuseIsNotWritten) {
  TriangleMesh mesh = RoundTripSubject();
  TempDir dir;
  for (const double far : {5.6e30, -2 * kMaxCoordinate}) {
    mesh.vertices[7].z() = far;
    for (const char* ext : {"obj", "off", "ply", "stl"}) {
      const auto path = dir / (std::string("far.") + ext);
      try {
        SaveMesh(mesh, path);
        ADD_FAILURE() << "no error for " << ext << " at " << far;
      } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(path.string() + ": cannot save: vertex 7 has |coordinate|", 0), 0u) << msg;
        EXPECT_NE(msg.find("beyond the 1e+09 m the mesh readers accept"), std::string::npos) << msg;
      }
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  }
  mesh.vertices[7].z() = -kMaxCoordinate;
  SaveMesh(mesh, dir / "edge.obj");
  EXPECT_EQ(LoadMesh(dir / "edge.obj").vertices[7].z(), -kMaxCoordinate);
}

TEST(StlWriter, RoundTripKeepsEveryCornerToFloatPrecisionAndWelds) {
  const TriangleMesh mesh = RoundTripSubject();
  TempDir dir;
  SaveMesh(mesh, dir / "torus.stl");
  const TriangleMesh loaded = LoadMesh(dir / "torus.stl");
  EXPECT_EQ(loaded.num_vertices(), mesh.num_vertices());  // shared vertices recovered
  ASSERT_EQ(loaded.num_triangles(), mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = mesh.vertices[mesh.triangles[t][k]];
      Eigen::Vector3d expected;
      for (int a = 0; a < 3; ++a) expected[a] = RoundToFloat(p[a]);
      EXPECT_EQ(loaded.vertices[loaded.triangles[t][k]], expected) << "triangle " << t << " corner " << k;
    }
  }
  EXPECT_TRUE(ValidateMesh(loaded).watertight);
}

TEST(LoadMesh, AppliesScaleThenCentringThenRotationThenTranslation) {
  TriangleMesh mesh;
  mesh.vertices = {{1, 2, 3}, {3, 2, 1}, {2, 4, 2}};
  mesh.triangles = {{0, 1, 2}};
  TempDir dir;
  SaveMesh(mesh, dir / "tri.obj");
  MeshLoadOptions options;
  options.scale = 0.3;
  options.center = true;
  options.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  options.translation = Eigen::Vector3d(0.1, -0.2, 0.3);
  const TriangleMesh loaded = LoadMesh(dir / "tri.obj", options);
  const Eigen::Vector3d box_centre(2, 3, 2);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d expected = options.rotation * (0.3 * mesh.vertices[i] - 0.3 * box_centre) + options.translation;
    EXPECT_LT((loaded.vertices[i] - expected).norm(), 1e-14) << i;
  }
  // Without centring the box centre stays where scaling puts it.
  options.center = false;
  const TriangleMesh uncentred = LoadMesh(dir / "tri.obj", options);
  EXPECT_LT((uncentred.vertices[0] - (options.rotation * (0.3 * mesh.vertices[0]) + options.translation)).norm(), 1e-14);
}

TEST(LoadMesh, RejectsNonPositiveScale) {
  TempDir dir;
  const auto path = WriteFixture(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  MeshLoadOptions options;
  options.scale = 0;
  EXPECT_THROW(LoadMesh(path, options), Error);
}

}  // namespace
}  // namespace contactlab
