// Bad mesh files: each must give one contactlab::Error naming the file and the line (text
// formats) or record and byte offset (binary formats), never a crash.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <random>

#include "geometry/mesh_io.h"
#include "geometry/mesh_readers.h"
#include "geometry/mesh_test_util.h"
#include "geometry/procedural_shapes.h"
#include "test_support.h"
#include "util/atomic_file.h"

namespace contactlab {
namespace {

using testing::ByteBuilder;
using testing::ExpectLoadError;
using testing::TempDir;
using testing::WriteFixture;

const char kTriangleObj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(MeshBadInput, MissingFileIsNamed) {
  TempDir dir;
  ExpectLoadError(dir / "nothing-here.obj", {"nothing-here.obj", "not found"});
}

TEST(MeshBadInput, UnknownExtensionIsNamed) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "mesh.xyz", kTriangleObj), {"mesh.xyz", "unknown mesh format '.xyz'"});
  ExpectLoadError(WriteFixture(dir / "noextension", kTriangleObj), {"noextension", "unknown mesh format"});
}

TEST(MeshBadInput, OffWithoutHeaderNamesLineOne) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "plain.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                  {"plain.off:1:", "not an OFF file"});
}

TEST(MeshBadInput, PlyWithoutMagicOrEndHeader) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "obj-in-disguise.ply", kTriangleObj), {"obj-in-disguise.ply:1:", "not a PLY file"});
  ExpectLoadError(WriteFixture(dir / "open.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"),
                  {"open.ply:3:", "no 'end_header'"});
}

TEST(MeshBadInput, TruncatedBinaryStlNamesTheRecordAndOffset) {
  ByteBuilder b;
  b.Text(std::string(80, ' ')).Put<std::uint32_t>(3);
  for (int i = 0; i < 12; ++i) b.Put<float>(float(i));  // record 0 complete
  b.Put<std::uint16_t>(0);
  for (int i = 0; i < 5; ++i) b.Put<float>(0.0f);  // record 1 cut short
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "short.stl", b.bytes()),
                  {"short.stl", "triangle 1", "byte offset 134", "truncated", "declares 3 triangles"});
}

TEST(MeshBadInput, TruncatedBinaryStlWithSolidHeaderIsStillReportedAsTruncated) {
  ByteBuilder b;
  std::string header = "solid fake";
  header.resize(80, '\0');
  b.Text(header).Put<std::uint32_t>(2);
  for (int i = 0; i < 12; ++i) b.Put<float>(1.0f);
  b.Put<std::uint16_t>(0);
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "short.stl", b.bytes()), {"short.stl", "triangle 1", "byte offset 134", "truncated"});
}

TEST(MeshBadInput, StlShorterThanItsHeader) {
  ByteBuilder b;
  b.Text("binary junk").Put<std::uint32_t>(1);
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "tiny.stl", b.bytes()), {"tiny.stl", "truncated"});
}

TEST(MeshBadInput, NonFiniteBinaryStlCoordinateNamesTheRecord) {
  ByteBuilder b;
  b.Text(std::string(80, ' ')).Put<std::uint32_t>(2);
  for (int t = 0; t < 2; ++t) {
    for (int i = 0; i < 12; ++i) b.Put<float>(t == 1 && i == 7 ? std::numeric_limits<float>::quiet_NaN() : float(i));
    b.Put<std::uint16_t>(0);
  }
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "nan.stl", b.bytes()), {"nan.stl", "triangle 1", "byte offset 134", "not finite"});
}

TEST(MeshBadInput, AsciiStlErrorsNameTheLine) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "bad.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 inf 0\n"),
                  {"bad.stl:5:", "not finite"});
  ExpectLoadError(WriteFixture(dir / "open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
                  {"open.stl:3:", "truncated"});
  ExpectLoadError(WriteFixture(dir / "two.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"),
                  {"two.stl:6:", "2 vertices"});
}

TEST(MeshBadInput, TruncatedAsciiStlIsRefusedNamingTheLine) {
  TempDir dir;
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  // Cut between facets: no 'endsolid'.
  ExpectLoadError(WriteFixture(dir / "noend.stl", "solid x\n" + facet + facet),
                  {"noend.stl:15:", "truncated", "'endsolid'", "line 1"});
  // Cut after 'endloop', before 'endfacet'.
  ExpectLoadError(WriteFixture(dir / "midfacet.stl", "solid x\n" + facet + facet.substr(0, facet.size() - 9)),
                  {"midfacet.stl:14:", "truncated", "facet opened on line 9"});
  // Cut after the 'facet' line.
  ExpectLoadError(WriteFixture(dir / "facetonly.stl", "solid x\n" + facet + "facet normal 0 0 1\n"),
                  {"facetonly.stl:9:", "truncated"});
  // Complete files still load.
  EXPECT_EQ(LoadMesh(WriteFixture(dir / "ok.stl", "solid x\n" + facet + facet + "endsolid x\n")).triangles.size(), 2u);
}

TEST(MeshBadInput, NamedPipeIsRefusedWithoutBlocking) {
  TempDir dir;
  const std::filesystem::path fifo = dir / "pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  ExpectLoadError(fifo, {"pipe.obj", "is a named pipe, not a mesh file"});
  ExpectLoadError(dir / "nothing.obj", {"nothing.obj", "mesh file not found"});
  std::filesystem::create_directory(dir / "folder.obj");
  ExpectLoadError(dir / "folder.obj", {"folder.obj", "is a folder, not a mesh file"});
}

TEST(MeshBadInput, HugeCoordinatesOrScaleSayTheyAreOutOfRange) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "far.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n"),
                  {"far.obj", "coordinates out of range", "1e+09"});
  MeshLoadOptions o;
  o.scale = 1e300;
  try {
    LoadMesh(WriteFixture(dir / "tri.obj", std::string(kTriangleObj) + "f 1 2 3\n"), o);
    ADD_FAILURE() << "scale 1e300 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("after scaling"), std::string::npos) << e.what();
  }
}

TEST(MeshBadInput, TruncatedBinaryPlyNamesTheElementRecordAndOffset) {
  ByteBuilder b;
  b.Text("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 2\nproperty list uchar int vertex_indices\nend_header\n");
  const std::size_t header_bytes = b.bytes().size();
  for (int i = 0; i < 9; ++i) b.Put<float>(float(i % 3 == i / 3));
  b.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2);  // face 0; face 1 missing
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "short.ply", b.bytes()),
                  {"short.ply", "'face' record 1 of 2", "byte offset " + std::to_string(header_bytes + 36 + 13),
                   "truncated"});
}

TEST(MeshBadInput, PlyWithFewerVerticesThanItsHeader) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "short.ply",
                               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 1 0\n"),
                  {"short.ply:12:", "after 3 of 4 'vertex' elements"});
}

TEST(MeshBadInput, PlyIndexOutOfRangeAndNanCoordinate) {
  TempDir dir;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  ExpectLoadError(WriteFixture(dir / "range.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                  {"range.ply:13:", "index 3 out of range"});
  ExpectLoadError(WriteFixture(dir / "nan.ply", header + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
                  {"nan.ply:11:", "not finite"});
  ByteBuilder b(/*big_endian=*/true);
  b.Text("ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
         "element face 1\nproperty list uchar uint vertex_indices\nend_header\n");
  for (int i = 0; i < 9; ++i) b.Put<double>(i == 4 ? std::numeric_limits<double>::infinity() : 0.5);
  b.Put<std::uint8_t>(3).Put<std::uint32_t>(0).Put<std::uint32_t>(1).Put<std::uint32_t>(2);
  ExpectLoadError(WriteFixture(dir / "inf.ply", b.bytes()), {"inf.ply", "'vertex' record 1 of 3", "not finite"});
}

TEST(MeshBadInput, OffWithFewerVerticesOrFacesThanItsCounts) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "v.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n"), {"v.off:5:", "after 3 of 4 vertices"});
  ExpectLoadError(WriteFixture(dir / "f.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                  {"f.off:6:", "after 1 of 2 faces"});
}

TEST(MeshBadInput, OffIndexOutOfRangeAndShortFace) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n"), {"r.off:6:", "out of range"});
  ExpectLoadError(WriteFixture(dir / "s.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), {"s.off:6:", "2 vertices"});
}

TEST(MeshBadInput, ObjNonFiniteCoordinatesNameTheLine) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), {"nan.obj:2:", "not finite"});
  ExpectLoadError(WriteFixture(dir / "inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 -inf\nf 1 2 3\n"), {"inf.obj:3:", "not finite"});
  ExpectLoadError(WriteFixture(dir / "huge.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"), {"huge.obj:2:", "not finite"});
  ExpectLoadError(WriteFixture(dir / "word.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n"), {"word.obj:2:", "'zero'"});
}

TEST(MeshBadInput, ObjZeroAndOutOfRangeIndicesNameTheLine) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "zero.obj", std::string(kTriangleObj) + "f 0 1 2\n"), {"zero.obj:4:", "index 0"});
  ExpectLoadError(WriteFixture(dir / "big.obj", std::string(kTriangleObj) + "f 1 2 4\n"),
                  {"big.obj:4:", "index 4 out of range"});
  ExpectLoadError(WriteFixture(dir / "neg.obj", std::string(kTriangleObj) + "f -1 -2 -4\n"),
                  {"neg.obj:4:", "index -4 out of range"});
  ExpectLoadError(WriteFixture(dir / "junk.obj", std::string(kTriangleObj) + "f 1 2 x/3\n"), {"junk.obj:4:", "'x/3'"});
}

TEST(MeshBadInput, FaceWithFewerThanThreeVerticesNamesTheLine) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "two.obj", std::string(kTriangleObj) + "f 1 2 3\nf 1 2\n"), {"two.obj:5:", "2 vertices"});
  ExpectLoadError(WriteFixture(dir / "two.ply",
                               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
                  {"two.ply:13:", "2 vertices"});
}

TEST(MeshBadInput, MeshWithoutTrianglesIsRejectedInEveryFormat) {
  TempDir dir;
  ExpectLoadError(WriteFixture(dir / "points.obj", kTriangleObj), {"points.obj", "no triangles"});
  ExpectLoadError(WriteFixture(dir / "empty.obj", ""), {"empty.obj", "no triangles"});
  ExpectLoadError(WriteFixture(dir / "points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"), {"points.off", "no triangles"});
  ExpectLoadError(WriteFixture(dir / "empty.off", ""), {"empty.off", "empty file"});
  ByteBuilder stl;
  stl.Text(std::string(80, ' ')).Put<std::uint32_t>(0);
  ExpectLoadError(WriteFixture(dir / "none.stl", stl.bytes()), {"none.stl", "no triangles"});
  ExpectLoadError(WriteFixture(dir / "none-ascii.stl", "solid x\nendsolid x\n"), {"none-ascii.stl", "no triangles"});
  ExpectLoadError(WriteFixture(dir / "cloud.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n0 0 0\n"),
                  {"cloud.ply", "no 'face' element"});
  ExpectLoadError(WriteFixture(dir / "nofaces.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n"),
                  {"nofaces.ply", "no triangles"});
}

// Parses BYTES with the reader for EXT, in memory (the prefix and noise test below makes
// thousands of inputs; files would only add disk traffic).
TriangleMesh ReadInMemory(const std::string& ext, const std::string& bytes) {
  if (ext == "obj") return internal::ReadObj(bytes, "mem.obj");
  if (ext == "off") return internal::ReadOff(bytes, "mem.off");
  if (ext == "stl") return internal::ReadStl(bytes, "mem.stl");
  return internal::ReadPly(bytes, "mem.ply");
}

// Every prefix of a valid file, and random bytes, either load or throw Error: never a crash,
// never another exception type.
TEST(MeshBadInput, EveryPrefixAndRandomBytesLoadOrThrowError) {
  TempDir dir;
  TriangleMesh mesh = MakeBox(Eigen::Vector3d(0.5, 0.25, 1));
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> byte(0, 255);
  for (const std::string ext : {"obj", "off", "stl", "ply"}) {
    SCOPED_TRACE(ext);
    const auto valid = dir / ("valid." + ext);
    SaveMesh(mesh, valid);
    const std::string bytes = ReadWholeFile(valid);
    EXPECT_EQ(ReadInMemory(ext, bytes).num_triangles(), 12);
    int errors = 0;
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      try {
        ReadInMemory(ext, bytes.substr(0, n));
      } catch (const Error&) {
        ++errors;
      }
    }
    EXPECT_GT(errors, 0);
    for (int trial = 0; trial < 200; ++trial) {
      // Odd trials: the valid file with 8 bytes changed; even trials: all random.
      std::string noise = trial % 2 ? bytes : std::string(bytes.size(), ' ');
      for (int k = 0; k < (trial % 2 ? 8 : int(noise.size())); ++k) noise[rng() % noise.size()] = char(byte(rng));
      try {
        ReadInMemory(ext, noise);
      } catch (const Error&) {
      }
    }
  }
}

// A PLY file whose last header line is "end_header" without a line break has an empty body:
// the body starts at the end of the file, not one byte past it (binary records were read
// beyond the buffer, an ASCII body threw std::out_of_range). Found by tests/fuzz/fuzz_ply_reader.
TEST(MeshBadInput, PlyEndHeaderWithoutLineBreakIsTruncatedNotReadPastTheEnd) {
  const std::string header =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header";
  for (const std::string format : {"binary_little_endian", "binary_big_endian", "ascii"}) {
    SCOPED_TRACE(format);
    for (const std::string tail : {"", " \t", "\t\xf6\xa3\xa3\xa3"}) {
      std::string message;
      try {
        ReadInMemory("ply", "ply\nformat " + format + " 1.0\n" + header + tail);
      } catch (const Error& e) {
        message = e.what();
      }
      EXPECT_NE(message.find("mem.ply"), std::string::npos) << message;
      if (format != "ascii") {
        EXPECT_NE(message.find("record 0 of 3"), std::string::npos) << message;
        EXPECT_NE(message.find("truncated"), std::string::npos) << message;
      }
    }
  }
}

// A binary PLY element without properties has records of no bytes: skipped at once, whatever
// its count (a count near 2^31 made the reader spin for seconds, minutes under sanitizers).
// Found by tests/fuzz/fuzz_ply_reader. Here a thousand such elements, before, between and after
// the mesh's, declare some 2^41 empty records in all. The reader's cost is counted, not timed:
// it may step through the mesh's four records (three vertices, one face) and no more, so a
// reader that visits the empty records one by one fails at its fifth instead of running for
// hours; and the mesh around them reads as if they were absent.
TEST(MeshBadInput, PlyElementWithoutPropertiesCostsNothingWhateverItsCount) {
  const auto ply = [](int empty_elements, int count) {
    std::string empty;
    for (int e = 0; e < empty_elements; ++e) empty += "element nothing" + std::to_string(e) + " " + std::to_string(count) + "\n";
    ByteBuilder b;
    b.Text("ply\nformat binary_little_endian 1.0\n" + empty + "element vertex 3\n"
           "property float x\nproperty float y\nproperty float z\n" + empty + "element face 1\n"
           "property list uchar int vertex_indices\n" + empty + "end_header\n");
    for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.Put<float>(v);
    b.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2);
    return b.bytes();
  };
  constexpr int kEmptyElements = 3 * (1000 / 3), kCount = 2147483646;  // the largest count the header takes
  internal::PlyReadStats plain_stats, padded_stats;
  plain_stats.max_records_visited = padded_stats.max_records_visited = 4;
  const TriangleMesh plain = internal::ReadPly(ply(0, 0), "plain.ply", &plain_stats);
  TriangleMesh padded;
  try {
    padded = internal::ReadPly(ply(kEmptyElements / 3, kCount), "padded.ply", &padded_stats);
  } catch (const Error& e) {
    FAIL() << "the empty records cost per-record work: " << e.what();
  }
  EXPECT_EQ(plain_stats.records_visited, 4);
  EXPECT_EQ(padded_stats.records_visited, 4);
  EXPECT_EQ(padded_stats.records_skipped, std::int64_t(kEmptyElements) * kCount);
  ASSERT_EQ(padded.num_triangles(), 1);
  ASSERT_EQ(padded.vertices.size(), 3u);
  EXPECT_EQ(padded.triangles, plain.triangles);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(padded.vertices[i], plain.vertices[i]) << "vertex " << i;
  EXPECT_EQ(padded.vertices[1], Eigen::Vector3d(1, 0, 0));
}

// The budget of the cost check above holds: a read that needs more records than allowed
// throws, naming the file and the record where it stopped.
TEST(MeshBadInput, PlyRecordBudgetStopsTheReadAtOnce) {
  ByteBuilder b;
  b.Text("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n");
  for (const float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.Put<float>(v);
  b.Put<std::uint8_t>(3).Put<std::int32_t>(0).Put<std::int32_t>(1).Put<std::int32_t>(2);
  internal::PlyReadStats stats;
  stats.max_records_visited = 2;
  try {
    internal::ReadPly(b.bytes(), "budget.ply", &stats);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("budget.ply"), std::string::npos) << message;
    EXPECT_NE(message.find("'vertex' record 2"), std::string::npos) << message;
    EXPECT_NE(message.find("more than 2 records"), std::string::npos) << message;
  }
  EXPECT_EQ(stats.records_visited, 3);
}

// A garbage token quoted in an error is cut short and its control bytes escaped: a
// ten-thousand-character token or an escape sequence from a broken file must neither flood
// nor drive the terminal. One case per place a reader quotes the file's text.
TEST(MeshBadInput, ErrorsNeverEchoLongTokensOrControlBytes) {
  const std::string huge(10000, '9'), garbage = "ab\x1b[2J\x07" + std::string(5000, 'x');
  const struct {
    const char* ext;
    std::string text;
  } cases[] = {
      {"obj", "v 0 0 0\nv 1 0 0\nv 0 1 " + huge + "e\nf 1 2 3\n"},    // ReadDouble
      {"obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " + garbage + "\n"},  // a face vertex
      {"off", garbage + "\n"},                                          // the header keyword
      {"off", "OFF " + garbage + "\n"},                                 // the header line
      {"off", "OFF\n" + huge + "x 1 0\n"},                              // ReadInt
      {"stl", "solid s\n" + std::string(5000, 'k') + "\n"},              // an unknown keyword
      {"ply", "ply\nformat " + garbage + " 1.0\n"},                     // the format
      {"ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty " + garbage + " x\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty list " + garbage + " int v\n"},
      {"ply", "ply\nformat ascii 1.0\n" + garbage + "\n"},              // a header line
      // An element named with garbage, its record cut short: the message names the element.
      {"ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nelement " + garbage +
                  " 2\nproperty float w\nend_header\n" + std::string(36, '\0') +
                  std::string("\x03\0\0\0\0\x01\0\0\0\x02\0\0\0", 13) + "\x01\x02"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.ext) + ": " + c.text.substr(0, 60));
    std::string message;
    try {
      ReadInMemory(c.ext, c.text);
    } catch (const Error& e) {
      message = e.what();
    }
    ASSERT_FALSE(message.empty()) << "no error";
    EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
    for (const char ch : message) {
      EXPECT_FALSE(static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) >= 0x7f)
          << "raw byte " << int(static_cast<unsigned char>(ch)) << " in: " << message;
    }
    EXPECT_TRUE(message.find("characters)") != std::string::npos || message.find("\\x1b") != std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace contactlab
