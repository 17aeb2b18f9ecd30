#include "pointshell/pointshell_io.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include <fstream>
#include <sstream>

#include "pointshell/analytic_fields.h"
#include "pointshell/build_pointshell.h"
#include "pointshell/pointshell_export.h"
#include "pointshell/pointshell_quality.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/binary_io.h"
#include "util/error.h"

namespace contactlab {
namespace {

const DistanceField& Sphere() {
  static const DistanceField field = testing::SampledSphere(0.3, 0.5, 33);
  return field;
}

const Pointshell& Shell() {
  static const Pointshell shell = [] {
    PointshellOptions o;
    o.num_points = 500;
    o.num_levels = 3;
    o.seed = 11;
    o.show_progress = false;
    return BuildPointshell(Sphere(), o);
  }();
  return shell;
}

using testing::ErrorOf;

// Writes SHELL's payload with the file layout but without validation (to make broken files).
void SaveUnchecked(const Pointshell& s, const std::filesystem::path& path) {
  BinaryWriter w;
  w.PutString(s.method);
  w.PutString(s.source);
  w.Put<double>(s.offset);
  w.Put<std::uint64_t>(s.seed);
  for (const auto* a : {&s.x, &s.y, &s.z, &s.nx, &s.ny, &s.nz}) w.PutArray(*a);
  w.PutArray(s.level_point_end);
  w.PutArray(s.level_node_begin);
  w.PutArray(s.node_point);
  w.PutArray(s.node_radius);
  w.PutArray(s.child_begin);
  w.PutArray(s.node_parent);
  w.Save(path, "CLPS", 1);
}

TEST(PointshellFile, RoundTripIsBitIdentical) {
  testing::TempDir dir;
  SavePointshell(Shell(), dir / "a.ps");
  const Pointshell b = LoadPointshell(dir / "a.ps");
  const Pointshell& a = Shell();
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.nx, b.nx);
  EXPECT_EQ(a.ny, b.ny);
  EXPECT_EQ(a.nz, b.nz);
  EXPECT_EQ(a.level_point_end, b.level_point_end);
  EXPECT_EQ(a.level_node_begin, b.level_node_begin);
  EXPECT_EQ(a.node_point, b.node_point);
  EXPECT_EQ(a.node_radius, b.node_radius);
  EXPECT_EQ(a.child_begin, b.child_begin);
  EXPECT_EQ(a.node_parent, b.node_parent);
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.offset, b.offset);
  EXPECT_EQ(a.seed, b.seed);
}

TEST(PointshellFile, TruncatedCorruptAndForeignFilesAreRejected) {
  testing::TempDir dir;
  SavePointshell(Shell(), dir / "a.ps");
  const std::string bytes = ReadWholeFile(dir / "a.ps");
  // Truncated.
  WriteFileAtomically(dir / "short.ps", std::string_view(bytes).substr(0, bytes.size() / 2));
  EXPECT_NE(ErrorOf([&] { LoadPointshell(dir / "short.ps"); }).find("short.ps"), std::string::npos);
  // One flipped byte in the payload: checksum mismatch.
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  WriteFileAtomically(dir / "flip.ps", flipped);
  EXPECT_NE(ErrorOf([&] { LoadPointshell(dir / "flip.ps"); }).find("flip.ps"), std::string::npos);
  // Another format's magic, and a missing file.
  std::string foreign = bytes;
  foreign[0] = 'X';
  WriteFileAtomically(dir / "foreign.ps", foreign);
  EXPECT_THROW(LoadPointshell(dir / "foreign.ps"), Error);
  EXPECT_THROW(LoadPointshell(dir / "missing.ps"), Error);
}

TEST(PointshellFile, StructurallyInvalidShellsAreRejectedOnLoadAndSave) {
  testing::TempDir dir;
  struct Case {
    std::string name, expected;
    std::function<void(Pointshell&)> breakit;
  };
  const std::vector<Case> cases = {
      {"parent", "parent not on the previous level", [](Pointshell& s) { s.node_parent.back() = 0; }},
      {"point", "point index out of range", [](Pointshell& s) { s.node_point[0] = 1 << 20; }},
      {"levels", "not strictly increasing", [](Pointshell& s) { s.level_point_end[1] = s.level_point_end[0]; }},
      {"normal", "not a unit vector", [](Pointshell& s) { s.nx[3] = 5; }},
      {"radius", "radius is negative", [](Pointshell& s) { s.node_radius[0] = -1; }},
      {"length", "differ in length", [](Pointshell& s) { s.y.pop_back(); }},
      {"children", "child range", [](Pointshell& s) { s.child_begin[1] = s.child_begin[0] - 1; }},
      {"self", "first child is not its own point",
       [](Pointshell& s) {  // swap the points of the first node's first two children
         const int c = s.child_begin[0];
         ASSERT_GE(s.child_begin[1] - c, 2);
         std::swap(s.node_point[c], s.node_point[c + 1]);
       }},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    Pointshell s = Shell();
    c.breakit(s);
    const auto path = dir / (c.name + ".ps");
    SaveUnchecked(s, path);
    const std::string load_error = ErrorOf([&] { LoadPointshell(path); });
    EXPECT_NE(load_error.find(c.expected), std::string::npos) << load_error;
    EXPECT_NE(load_error.find(c.name + ".ps"), std::string::npos) << load_error;
    EXPECT_THROW(SavePointshell(s, dir / "never.ps"), Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "never.ps"));
  }
}

// Every float of the export reads back as the same float (they were printed with %.9g, which
// holds a float, but through one shared helper now, util/number_text.h).
TEST(PointshellExport, CsvReadsBackBitForBit) {
  testing::TempDir dir;
  const Pointshell& s = Shell();
  ExportPointshell(s, s.num_levels() - 1, dir / "all.csv");
  std::ifstream csv(dir / "all.csv");
  std::string line;
  std::getline(csv, line);
  for (int i = 0; i < s.num_points(); ++i) {
    ASSERT_TRUE(std::getline(csv, line));
    std::stringstream ss(line);
    std::string cell;
    const float expected[6] = {s.x[i], s.y[i], s.z[i], s.nx[i], s.ny[i], s.nz[i]};
    for (int c = 0; c < 6; ++c) {
      std::getline(ss, cell, ',');
      EXPECT_EQ(std::strtof(cell.c_str(), nullptr), expected[c]) << line;
    }
  }
}

TEST(PointshellExport, PlyAndCsvHoldTheRequestedLevel) {
  testing::TempDir dir;
  const Pointshell& s = Shell();
  ExportPointshell(s, 1, dir / "l1.ply");
  std::ifstream ply(dir / "l1.ply");
  std::string line;
  int vertices = -1, data_lines = 0;
  bool header = true;
  while (std::getline(ply, line)) {
    if (header) {
      if (line.rfind("element vertex ", 0) == 0) vertices = std::stoi(line.substr(15));
      if (line == "end_header") header = false;
    } else {
      ++data_lines;
    }
  }
  EXPECT_EQ(vertices, s.level_point_end[1]);
  EXPECT_EQ(data_lines, s.level_point_end[1]);

  ExportPointshell(s, 2, dir / "all.csv");
  std::ifstream csv(dir / "all.csv");
  std::getline(csv, line);
  EXPECT_EQ(line, "x,y,z,nx,ny,nz,level,parent,radius");
  int rows = 0;
  while (std::getline(csv, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 9u) << line;
    const int level = std::stoi(cells[6]), parent = std::stoi(cells[7]);
    const int expected_level = rows < s.level_point_end[0] ? 0 : rows < s.level_point_end[1] ? 1 : 2;
    EXPECT_EQ(level, expected_level) << rows;
    if (level == 0) EXPECT_EQ(parent, -1);
    else EXPECT_LT(parent, s.level_point_end[level - 1]);
    EXPECT_EQ(std::stod(cells[8]), 0.0);  // deepest level: leaves
    ++rows;
  }
  EXPECT_EQ(rows, s.num_points());
  EXPECT_THROW(ExportPointshell(s, 3, dir / "x.csv"), Error);
  EXPECT_THROW(ExportPointshell(s, 0, dir / "x.txt"), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.csv"));
}

TEST(PointshellQuality, JsonAndTextReportEveryLevel) {
  const PointshellQuality q = AssessPointshell(Shell(), &Sphere(), {5000});
  const nlohmann::json j = QualityToJson(q);
  ASSERT_EQ(j["levels"].size(), 3u);
  EXPECT_EQ(j["levels"][2]["points"], 500);
  EXPECT_GT(j["levels"][0]["covering_radius_m"].get<double>(), j["levels"][2]["covering_radius_m"].get<double>());
  EXPECT_EQ(j["coverage_samples"], 5000);
  // Without a field the field-dependent measures are null.
  const nlohmann::json k = QualityToJson(AssessPointshell(Shell(), nullptr));
  EXPECT_TRUE(k["levels"][0]["covering_radius_m"].is_null());
  EXPECT_GT(k["levels"][0]["spacing_mean_m"].get<double>(), 0);
  EXPECT_NE(QualityToText(q).find("cover_max_m"), std::string::npos);
}

}  // namespace
}  // namespace contactlab
