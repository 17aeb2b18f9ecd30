// Distance-field files and CSV points: round trips and every kind of bad input (sec. 2.3).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "sdf/point_csv.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/binary_io.h"
#include "util/error.h"

namespace contactlab {
namespace {

DistanceField SmallField() {
  DistanceFieldOptions o;
  o.resolution = 12;
  o.show_progress = false;
  TriangleMesh m = MakeSphere(0.2, 1);
  m.name = "small sphere";
  return BuildDistanceField(m, o);
}

// Expects LOAD to throw an Error whose message contains every one of PARTS.
template <typename F>
void ExpectErrorMentioning(F load, std::initializer_list<std::string> parts) {
  try {
    load();
    FAIL() << "no error";
  } catch (const Error& e) {
    for (const auto& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(DistanceFieldFile, RoundTripKeepsGridValuesAndInfo) {
  testing::TempDir dir;
  const DistanceField f = SmallField();
  SaveDistanceField(f, dir / "f.sdf");
  const DistanceField g = LoadDistanceField(dir / "f.sdf");
  EXPECT_EQ(g.dims(), f.dims());
  EXPECT_EQ(g.origin(), f.origin());
  EXPECT_EQ(g.spacing(), f.spacing());
  EXPECT_EQ(g.values(), f.values());
  EXPECT_EQ(g.info().source, "small sphere");
  EXPECT_EQ(g.info().mode, "closed");
  EXPECT_EQ(g.info().build_seconds, f.info().build_seconds);
}

TEST(DistanceFieldFile, TruncatedFileIsRejectedNamingIt) {
  testing::TempDir dir;
  SaveDistanceField(SmallField(), dir / "f.sdf");
  std::string bytes = ReadWholeFile(dir / "f.sdf");
  WriteFileAtomically(dir / "cut.sdf", std::string_view(bytes).substr(0, bytes.size() / 2));
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "cut.sdf"); }, {"cut.sdf"});
}

TEST(DistanceFieldFile, CorruptByteIsRejectedNamingTheFile) {
  testing::TempDir dir;
  SaveDistanceField(SmallField(), dir / "f.sdf");
  std::string bytes = ReadWholeFile(dir / "f.sdf");
  bytes[bytes.size() / 2] ^= 0x5a;
  WriteFileAtomically(dir / "bad.sdf", bytes);
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "bad.sdf"); }, {"bad.sdf"});
}

TEST(DistanceFieldFile, OtherFileKindIsRejected) {
  testing::TempDir dir;
  BinaryWriter w;
  w.Put<double>(1.0);
  w.Save(dir / "other.bin", "CLPSHELL", 1);
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "other.bin"); }, {"other.bin"});
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "missing.sdf"); }, {"missing.sdf"});
}

TEST(DistanceFieldFile, InconsistentContentIsRejectedAsCorrupt) {
  testing::TempDir dir;
  // Valid container, but the dimensions do not match the samples.
  BinaryWriter w;
  for (int a = 0; a < 4; ++a) w.Put<double>(a == 3 ? 0.1 : 0.0);
  for (int a = 0; a < 3; ++a) w.Put<std::int32_t>(3);
  w.PutArray(std::vector<float>(26, 1.f));
  w.PutString("x");
  w.PutString("closed");
  w.Put<double>(0);
  w.Put<double>(0);
  w.Save(dir / "dims.sdf", "CLSDF", 1);
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "dims.sdf"); }, {"dims.sdf", "corrupt"});
  // A NaN sample.
  BinaryWriter n;
  for (int a = 0; a < 4; ++a) n.Put<double>(a == 3 ? 0.1 : 0.0);
  for (int a = 0; a < 3; ++a) n.Put<std::int32_t>(2);
  std::vector<float> v(8, 1.f);
  v[5] = std::nanf("");
  n.PutArray(v);
  n.PutString("x");
  n.PutString("closed");
  n.Put<double>(0);
  n.Put<double>(0);
  n.Save(dir / "nan.sdf", "CLSDF", 1);
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "nan.sdf"); }, {"nan.sdf", "not finite"});
}

TEST(DistanceFieldFile, ChecksumValidFileWithHugeSpacingIsRefused) {
  testing::TempDir dir;
  BinaryWriter w;
  for (int a = 0; a < 4; ++a) w.Put<double>(a == 3 ? 1e300 : 0.0);
  for (int a = 0; a < 3; ++a) w.Put<std::int32_t>(2);
  w.PutArray(std::vector<float>(8, 1.f));
  w.PutString("x");
  w.PutString("closed");
  w.Put<double>(0);
  w.Put<double>(0);
  w.Save(dir / "huge.sdf", "CLSDF", 1);
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "huge.sdf"); }, {"huge.sdf", "out of range", "1e+09"});
}

TEST(DistanceFieldFile, NamedPipeIsRefusedWithoutBlocking) {
  testing::TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "pipe.sdf").c_str(), 0600), 0);
  ExpectErrorMentioning([&] { LoadDistanceField(dir / "pipe.sdf"); }, {"pipe.sdf", "is a named pipe, not a file"});
}

TEST(DistanceFieldFile, DescriptionNamesModeGridAndSoupOffset) {
  DistanceField f = SmallField();
  std::string text = DescribeDistanceField(f);
  EXPECT_NE(text.find("small sphere"), std::string::npos) << text;
  EXPECT_NE(text.find("13 x 13 x 13"), std::string::npos) << text;
  f.mutable_info().mode = "soup";
  f.mutable_info().offset = 0.0125;
  text = DescribeDistanceField(f);
  EXPECT_NE(text.find("offset surface at distance 0.0125"), std::string::npos) << text;
}

TEST(PointsCsv, ReadsRowsWithOptionalHeaderAndWritesDistances) {
  testing::TempDir dir;
  WriteFileAtomically(dir / "p.csv", std::string("x,y,z\n1, 2.5 ,-3\n\n0.125,1e-3,4\n"));
  const auto points = ReadPointsCsv(dir / "p.csv");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], Eigen::Vector3d(1, 2.5, -3));
  EXPECT_EQ(points[1], Eigen::Vector3d(0.125, 1e-3, 4));
  WritePointDistancesCsv(dir / "out.csv", points, {0.5, -0.25});
  EXPECT_EQ(ReadWholeFile(dir / "out.csv"), "x,y,z,d\n1,2.5,-3,0.5\n0.125,0.001,4,-0.25\n");
}

// A distance that is not finite (a deformed field at overflowing coordinates) is refused, naming
// the file and the row, and no file is written.
TEST(PointsCsv, ANonFiniteDistanceIsRefusedAndNothingWritten) {
  testing::TempDir dir;
  const std::vector<Eigen::Vector3d> points = {{1, 2, 3}, {4, 5, 6}};
  ExpectErrorMentioning(
      [&] { WritePointDistancesCsv(dir / "d.csv", points, {0.5, std::numeric_limits<double>::infinity()}); },
      {(dir / "d.csv").string(), "row 3 distance d is inf"});
  EXPECT_FALSE(std::filesystem::exists(dir / "d.csv"));
  ExpectErrorMentioning([&] { WritePointDistancesCsv(dir / "d.csv", {{std::nan(""), 0, 0}}, {0.5}); },
                        {(dir / "d.csv").string(), "row 2 point is nan"});
  EXPECT_FALSE(std::filesystem::exists(dir / "d.csv"));
}

// x, y, z and d read back bit for bit (values decimal cannot hold).
TEST(PointsCsv, WrittenDistancesReadBackBitForBit) {
  testing::TempDir dir;
  const std::vector<Eigen::Vector3d> points = {{1.0 / 3, -2.0 / 7, 1e-17 / 3}, {0.1, 0.7, 123456.789012345678}};
  const std::vector<double> d = {std::sqrt(2.0) / 1e5, -1.0 / 3};
  WritePointDistancesCsv(dir / "d.csv", points, d);
  std::istringstream in(ReadWholeFile(dir / "d.csv"));
  std::string line;
  std::getline(in, line);
  for (std::size_t n = 0; n < points.size(); ++n) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream cells(line);
    std::string cell;
    for (int c = 0; c < 4; ++c) {
      std::getline(cells, cell, ',');
      EXPECT_EQ(std::strtod(cell.c_str(), nullptr), c < 3 ? points[n][c] : d[n]) << line;
    }
  }
}

TEST(PointsCsv, BadRowIsRejectedNamingFileAndLine) {
  testing::TempDir dir;
  WriteFileAtomically(dir / "bad.csv", std::string("x,y,z\n1,2,3\n1,two,3\n"));
  ExpectErrorMentioning([&] { ReadPointsCsv(dir / "bad.csv"); }, {"bad.csv:3", "two"});
  WriteFileAtomically(dir / "short.csv", std::string("1,2,3\n4,5\n"));
  ExpectErrorMentioning([&] { ReadPointsCsv(dir / "short.csv"); }, {"short.csv:2", "3 fields"});
  WriteFileAtomically(dir / "inf.csv", std::string("1,2,inf\n"));
  ExpectErrorMentioning([&] { ReadPointsCsv(dir / "inf.csv"); }, {"inf.csv:1"});
  ExpectErrorMentioning([&] { ReadPointsCsv(dir / "missing.csv"); }, {"missing.csv"});
}

TEST(PointsCsv, UnparsableFirstRowIsAnErrorNotAHeader) {
  testing::TempDir dir;
  for (const char* first : {"1;2;3", "1 2 3", "1e400,0,0", "x,2,3"}) {
    WriteFileAtomically(dir / "p.csv", std::string(first) + "\n4,5,6\n");
    ExpectErrorMentioning([&] { ReadPointsCsv(dir / "p.csv"); }, {"p.csv:1:"});
  }
  WriteFileAtomically(dir / "p.csv", std::string("1e400,0,0\n"));
  ExpectErrorMentioning([&] { ReadPointsCsv(dir / "p.csv"); }, {"p.csv:1:", "'1e400'", "out of range"});
  // Names are still a header.
  WriteFileAtomically(dir / "p.csv", std::string("x (m), y_m ,Z\n4,5,6\n"));
  EXPECT_EQ(ReadPointsCsv(dir / "p.csv").size(), 1u);
}

}  // namespace
}  // namespace contactlab
