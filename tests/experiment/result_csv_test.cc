// The result tables' columns are declared once: header and rows always agree.
#include "experiment/result_csv.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace contactlab {
namespace {

std::vector<std::vector<std::string>> Rows(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(SplitCsvLine(line));
  return rows;
}

TEST(ResultCsv, HeaderAndRowsHaveTheSameColumnsAndEmptyCellsWithoutAReference) {
  ExperimentConfig config;
  config.name = "exp";
  config.sweep = {{"points", "", {"64", "128"}, {}}, {"k_C", "", {"500"}, {}}};
  JobResult r;
  r.job.index = 1;
  r.job.axis_values = {{"points", "128"}, {"k_C", "500"}};
  CycleRow a;
  a.model = "fcl";
  a.force = Eigen::Vector3d(1.5, -2, 0.25);
  CycleRow b = a;
  b.cycle = 1;
  b.has_reference = true;
  b.reference_force = Eigen::Vector3d(3, 4, 5);
  r.cycles = {a, b};
  SummaryRow s;
  s.model = "fcl";
  s.points = 128;
  r.summary = {s};

  std::string cycles = CyclesCsvHeader(config);
  AppendCyclesCsv(config, r, &cycles);
  const auto c = Rows(cycles);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0][0], "experiment");
  EXPECT_EQ(c[0][2], "points");
  EXPECT_EQ(c[0][3], "k_C");
  EXPECT_EQ(c[0][4], "model");
  EXPECT_EQ(c[0].back(), "q_B");
  for (const auto& row : c) EXPECT_EQ(row.size(), c[0].size());
  const auto col = [&](const std::string& name) {
    return std::size_t(std::find(c[0].begin(), c[0].end(), name) - c[0].begin());
  };
  EXPECT_EQ(c[1][0], "exp");
  EXPECT_EQ(c[1][1], "1");
  EXPECT_EQ(c[1][2], "128");
  EXPECT_EQ(std::stod(c[1][col("fy")]), -2);
  EXPECT_EQ(c[1][col("ref_fx")], "");
  EXPECT_EQ(c[1][col("ref_fz")], "");
  EXPECT_EQ(std::stod(c[2][col("ref_fy")]), 4);
  // A rigid body's rows leave the deformation columns empty.
  EXPECT_EQ(c[1][col("elastic_energy_J")], "");
  EXPECT_EQ(c[1][col("q")], "");

  std::string summary = SummaryCsvHeader(config);
  AppendSummaryCsv(config, r, &summary);
  const auto t = Rows(summary);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].size(), t[0].size());
  EXPECT_EQ(t[0][5], "points");
  EXPECT_EQ(t[1][5], "128");
}

TEST(ResultCsv, MemoryColumnsAreIntegerBytesOrEmptyForDataAModelDoesNotRead) {
  ExperimentConfig config;
  config.name = "exp";
  JobResult r;
  SummaryRow reads;  // a model that reads the field and the pointshell
  reads.model = "pointshell";
  reads.field_B_bytes = 3'000'000'000LL;  // beyond 32 bits: a 1024-cell field
  reads.pointshell_A_bytes = 123456;
  SummaryRow meshes_only;  // one that reads neither (field_B_bytes, pointshell_A_bytes = -1)
  meshes_only.model = "fcl";
  r.summary = {reads, meshes_only};
  std::string summary = SummaryCsvHeader(config);
  AppendSummaryCsv(config, r, &summary);
  const auto t = Rows(summary);
  ASSERT_EQ(t.size(), 3u);
  const auto col = [&](const std::string& name) {
    const auto it = std::find(t[0].begin(), t[0].end(), name);
    EXPECT_NE(it, t[0].end()) << name;
    return std::size_t(it - t[0].begin());
  };
  EXPECT_EQ(t[1][col("field_B_bytes")], "3000000000");
  EXPECT_EQ(t[1][col("pointshell_A_bytes")], "123456");
  EXPECT_EQ(t[2][col("field_B_bytes")], "");
  EXPECT_EQ(t[2][col("pointshell_A_bytes")], "");
}

}  // namespace
}  // namespace contactlab
