// Gzip-compressed meshes (.obj.gz, .off.gz, .stl.gz, .ply.gz): LoadMesh must give exactly the
// mesh the uncompressed file gives, and a damaged .gz must fail with an error naming the file.
// The compressed fixtures are written by zlib's own gzip writer (gzwrite), not by our reader.
#include <gtest/gtest.h>
#include <zlib.h>

#include <string>

#include "geometry/mesh_io.h"
#include "geometry/mesh_test_util.h"
#include "geometry/procedural_shapes.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/gzip_file.h"

namespace contactlab {
namespace {

using testing::TempDir;
using testing::WriteFixture;

// Writes BYTES to PATH as a gzip file through zlib's gzwrite.
std::filesystem::path GzipFixture(const std::filesystem::path& path, const std::string& bytes) {
  gzFile out = gzopen(path.c_str(), "wb9");
  EXPECT_NE(out, nullptr);
  EXPECT_EQ(gzwrite(out, bytes.data(), static_cast<unsigned>(bytes.size())), static_cast<int>(bytes.size()));
  EXPECT_EQ(gzclose(out), Z_OK);
  return path;
}

// Expects LoadMesh(PATH) to throw Error whose message contains every one of PARTS.
void ExpectLoadError(const std::filesystem::path& path, const std::vector<std::string>& parts) {
  try {
    LoadMesh(path);
    FAIL() << path << " loaded";
  } catch (const Error& e) {
    const std::string m = e.what();
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
  }
}

class GzipMesh : public ::testing::TestWithParam<const char*> {};

// A torus with positions that are not exact in binary, saved in each format, then gzipped:
// the compressed and the plain file load to the same vertices (bit for bit) and triangles.
TEST_P(GzipMesh, LoadsExactlyAsTheUncompressedFile) {
  TempDir dir;
  TriangleMesh torus = MakeTorus(1.0 / 3, 1.0 / 7, 24, 12);
  const std::filesystem::path plain = dir / (std::string("torus") + GetParam());
  SaveMesh(torus, plain);
  const std::filesystem::path gz = GzipFixture(dir / (std::string("torus") + GetParam() + ".gz"), ReadWholeFile(plain));
  const TriangleMesh a = LoadMesh(plain);
  const TriangleMesh b = LoadMesh(gz);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_triangles(), b.num_triangles());
  for (int v = 0; v < a.num_vertices(); ++v) EXPECT_EQ(a.vertices[v], b.vertices[v]) << "vertex " << v;
  for (int t = 0; t < a.num_triangles(); ++t) EXPECT_EQ(a.triangles[t], b.triangles[t]) << "triangle " << t;
  EXPECT_EQ(b.name, plain.filename().string());  // named without ".gz"
  EXPECT_GT(b.num_triangles(), 500);
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, GzipMesh, ::testing::Values(".obj", ".off", ".stl", ".ply"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param + 1); });

TEST(GzipMesh, UpperCaseSuffixAndLoadOptionsApply) {
  TempDir dir;
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const TriangleMesh m = LoadMesh(GzipFixture(dir / "tri.OBJ.GZ", obj), MeshLoadOptions{.scale = 0.25});
  ASSERT_EQ(m.num_triangles(), 1);
  EXPECT_DOUBLE_EQ(m.vertices[1].x(), 0.25);
}

// gzip allows several members one after another; they decompress to the concatenation.
TEST(GzipMesh, ConcatenatedMembersAreOneFile) {
  TempDir dir;
  const std::string first = ReadWholeFile(GzipFixture(dir / "a.gz", "v 0 0 0\nv 1 0 0\n"));
  const std::string second = ReadWholeFile(GzipFixture(dir / "b.gz", "v 0 1 0\nf 1 2 3\n"));
  const TriangleMesh m = LoadMesh(WriteFixture(dir / "two.obj.gz", first + second));
  EXPECT_EQ(m.num_vertices(), 3);
  EXPECT_EQ(m.num_triangles(), 1);
  EXPECT_EQ(GunzipBytes(first + second, "x"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}

TEST(GzipMesh, DamagedFilesFailNamingTheFile) {
  TempDir dir;
  std::string text;
  for (int i = 0; i < 2000; ++i) text += "v " + std::to_string(i / 7.0) + " 0 " + std::to_string(i % 13) + "\n";
  text += "f 1 2 3\n";
  const std::string good = ReadWholeFile(GzipFixture(dir / "good.obj.gz", text));
  ASSERT_EQ(LoadMesh(dir / "good.obj.gz").num_triangles(), 1);

  // Not gzip at all: a plain OBJ named .obj.gz.
  ExpectLoadError(WriteFixture(dir / "plain.obj.gz", text), {"plain.obj.gz", "not a gzip file"});
  // Cut in half: the deflate stream ends early.
  ExpectLoadError(WriteFixture(dir / "half.obj.gz", good.substr(0, good.size() / 2)), {"half.obj.gz", "truncated"});
  // Flipped bits in the deflate data.
  std::string flipped = good;
  for (std::size_t i = 20; i < 60; ++i) flipped[i] = static_cast<char>(flipped[i] ^ 0x5a);
  ExpectLoadError(WriteFixture(dir / "flipped.obj.gz", flipped), {"flipped.obj.gz", "corrupt gzip data"});
  // A wrong CRC-32 in the trailer (the data itself inflates fine).
  std::string bad_crc = good;
  bad_crc[bad_crc.size() - 8] = static_cast<char>(bad_crc[bad_crc.size() - 8] ^ 1);
  ExpectLoadError(WriteFixture(dir / "crc.obj.gz", bad_crc), {"crc.obj.gz", "corrupt gzip data", "check"});
  // Garbage after the stream.
  ExpectLoadError(WriteFixture(dir / "tail.obj.gz", good + "junk"), {"tail.obj.gz", "garbage after the gzip stream"});
  // An unknown format inside the .gz.
  ExpectLoadError(GzipFixture(dir / "mesh.xyz.gz", text), {"mesh.xyz.gz", "unknown mesh format '.xyz.gz'"});
  // Parse errors inside still name the compressed file and the line.
  ExpectLoadError(GzipFixture(dir / "nan.obj.gz", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), {"nan.obj.gz:2:", "not finite"});
}

}  // namespace
}  // namespace contactlab
