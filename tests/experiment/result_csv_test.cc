// The result tables' columns are declared once: header and rows always agree, and cycles.csv
// reads back through the same columns to the rows written.
#include "experiment/studies/contact/result_csv.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "test_support.h"
#include "util/atomic_file.h"

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
  // The points axis is named like summary.csv's own points column: it is written sweep.points,
  // so every name in the header is unique (pandas renames none).
  EXPECT_EQ(t[0][2], "sweep.points");
  EXPECT_EQ(t[0][3], "k_C");
  EXPECT_EQ(t[0][5], "points");
  EXPECT_EQ(std::set<std::string>(t[0].begin(), t[0].end()).size(), t[0].size());
  EXPECT_EQ(t[1][2], "128");
  // FCL reads no pointshell (pointshell_A_bytes -1): its points cell is empty, as is every
  // error against a reference when there was none.
  EXPECT_EQ(t[1][5], "");
  for (const char* name : {"rms_rel_error", "max_dir_error_deg", "median_dir_error_deg", "p95_dir_error_deg",
                           "ref_scale", "rms_rel_error_calibrated"}) {
    const auto it = std::find(t[0].begin(), t[0].end(), name);
    ASSERT_NE(it, t[0].end()) << name;
    EXPECT_EQ(t[1][std::size_t(it - t[0].begin())], "") << name;
  }
  // A model that walks no tree (level -1) leaves cycles.csv's level empty.
  EXPECT_EQ(c[1][col("level")], "");
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

// The rows of a two-job run of an experiment swept over points and k_C: a rigid model (one row
// without and one with a reference force) and a model with deformable bodies (A: 3
// coordinates, B: 1) in job 0; the deformable model with 2 coordinates of A in job 1 (a sweep
// over the modes). Every value is exact at the precision its column is written with; q holds
// 1/3, which is not.
struct TwoJobs {
  ExperimentConfig config;
  JobResult job0, job1;
  std::vector<double> q0 = {1.5e-3, -2.25e-4, 1.0 / 3}, q0_B = {0.5}, q1 = {-7.5, 0.0625};

  TwoJobs() {
    config.name = "exp";
    config.sweep = {{"points", "", {"64", "128"}, {}}, {"k_C", "", {"500"}, {}}};
    job0.job.index = 0;
    job0.job.axis_values = {{"points", "64"}, {"k_C", "500"}};
    job1.job.index = 1;
    job1.job.axis_values = {{"points", "128"}, {"k_C", "500"}};
    CycleRow rigid;
    rigid.model = "fcl";
    rigid.cycle = 0;
    rigid.t = 0.125;
    rigid.position = Eigen::Vector3d(0.0125, -0.25, 1.5);
    rigid.rotation = Eigen::Quaterniond(0.5, 0.5, -0.5, 0.5);
    rigid.force = Eigen::Vector3d(1.5, -2, 0.25);
    rigid.torque = Eigen::Vector3d(-0.003, 0, 4e-5);
    rigid.contacts = 7;
    rigid.nodes = 12345678901;  // beyond 32 bits
    rigid.level = -1;
    rigid.max_penetration = 0.00125;
    rigid.depth_voxels = 0.25;
    rigid.contact_area = 3.5e-4;
    rigid.patches = 2;
    rigid.time_us = 12.5;
    CycleRow referenced = rigid;
    referenced.cycle = 1;
    referenced.t = 0.126;
    referenced.has_reference = true;
    referenced.reference_force = Eigen::Vector3d(3, -4, 5.5);
    CycleRow deformable = rigid;
    deformable.model = "pointshell";
    deformable.level = 2;
    deformable.deformable = true;
    deformable.step_us = 3.25;
    deformable.step_B_us = 1.75;
    deformable.elastic_energy = 2.5e-6;
    deformable.kinetic_energy = 1e-7;
    deformable.max_displacement = 0.0004;
    deformable.q = q0;
    deformable.q_B = q0_B;
    job0.cycles = {rigid, referenced, deformable};
    deformable.q = q1;
    deformable.q_B = {};
    deformable.step_B_us = 0;
    job1.cycles = {deformable};
  }
  std::string Csv() const {
    std::string text = CyclesCsvHeader(config);
    AppendCyclesCsv(config, job0, &text);
    AppendCyclesCsv(config, job1, &text);
    return text;
  }
};

std::vector<CyclesCsvRow> ReadAll(const std::filesystem::path& file, std::vector<std::string>* axes = nullptr) {
  std::vector<CyclesCsvRow> records;
  const std::vector<std::string> a = ReadCyclesCsv(file, [&](const CyclesCsvRow& r) { records.push_back(r); });
  if (axes) *axes = a;
  return records;
}

TEST(ResultCsv, CyclesReadBackAreTheRowsWritten) {
  testing::TempDir dir;
  const TwoJobs run;
  WriteFileAtomically(dir / "cycles.csv", run.Csv());
  std::vector<std::string> axes;
  const std::vector<CyclesCsvRow> back = ReadAll(dir / "cycles.csv", &axes);
  EXPECT_EQ(axes, (std::vector<std::string>{"points", "k_C"}));
  ASSERT_EQ(back.size(), 4u);

  const CycleRow* written[] = {&run.job0.cycles[0], &run.job0.cycles[1], &run.job0.cycles[2], &run.job1.cycles[0]};
  const int jobs[] = {0, 0, 0, 1};
  for (std::size_t i = 0; i < back.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    const CyclesCsvRow& r = back[i];
    const CycleRow& w = *written[i];
    const CycleRow& v = r.values;
    EXPECT_EQ(r.line, long(i) + 2);
    EXPECT_EQ(r.experiment, "exp");
    EXPECT_EQ(r.job, jobs[i]);
    EXPECT_EQ(r.axis_values, (std::vector<std::string>{jobs[i] == 0 ? "64" : "128", "500"}));
    EXPECT_EQ(r.model, w.model);
    EXPECT_EQ(v.cycle, w.cycle);
    EXPECT_EQ(v.t, w.t);
    EXPECT_EQ(v.position, w.position);
    EXPECT_EQ(v.rotation.coeffs(), w.rotation.coeffs());
    EXPECT_EQ(v.force, w.force);
    EXPECT_EQ(v.torque, w.torque);
    EXPECT_EQ(v.contacts, 7);
    EXPECT_EQ(v.nodes, 12345678901);
    EXPECT_EQ(v.level, w.level);
    EXPECT_EQ(v.max_penetration, 0.00125);
    EXPECT_EQ(v.depth_voxels, 0.25);
    EXPECT_EQ(v.contact_area, 3.5e-4);
    EXPECT_EQ(v.patches, 2);
    EXPECT_EQ(v.time_us, 12.5);
    EXPECT_EQ(v.has_reference, w.has_reference);
    if (w.has_reference) {
      EXPECT_EQ(v.reference_force, w.reference_force);
    }
    EXPECT_EQ(v.deformable, w.deformable);
    EXPECT_EQ(v.step_us, w.step_us);
    EXPECT_EQ(v.step_B_us, w.step_B_us);
    EXPECT_EQ(v.elastic_energy, w.elastic_energy);
    EXPECT_EQ(v.kinetic_energy, w.kinetic_energy);
    EXPECT_EQ(v.max_displacement, w.max_displacement);
  }
  // The reduced coordinates: none for the rigid rows, each number once (1/3 to the nine
  // significant digits it is written with).
  EXPECT_TRUE(back[0].q.empty() && back[0].q_B.empty());
  EXPECT_TRUE(back[1].q.empty() && back[1].q_B.empty());
  ASSERT_EQ(back[2].q.size(), 3u);
  EXPECT_EQ(back[2].q[0], 1.5e-3);
  EXPECT_EQ(back[2].q[1], -2.25e-4);
  EXPECT_NEAR(back[2].q[2], 1.0 / 3, 1e-9 / 3);
  EXPECT_EQ(back[2].q_B, std::vector<double>{0.5});
  EXPECT_EQ(back[3].q, (std::vector<double>{-7.5, 0.0625}));
  EXPECT_TRUE(back[3].q_B.empty());

  // Written again, the records are the same file.
  JobResult again0 = run.job0, again1 = run.job1;
  again0.cycles = {back[0].row(), back[1].row(), back[2].row()};
  again1.cycles = {back[3].row()};
  std::string text = CyclesCsvHeader(run.config);
  AppendCyclesCsv(run.config, again0, &text);
  AppendCyclesCsv(run.config, again1, &text);
  EXPECT_EQ(text, run.Csv());
}

// CSV TEXT with the cell of COLUMN on line LINE (1: the header) set to VALUE.
std::string WithCell(const std::string& text, long line, const std::string& column, const std::string& value) {
  std::istringstream in(text);
  std::vector<std::vector<std::string>> rows;
  for (std::string l; std::getline(in, l);) rows.push_back(SplitCsvLine(l));
  const std::size_t c = std::size_t(std::find(rows[0].begin(), rows[0].end(), column) - rows[0].begin());
  EXPECT_LT(c, rows[0].size()) << column;
  rows.at(std::size_t(line - 1)).at(c) = value;
  std::string out;
  for (const auto& row : rows) {
    for (std::size_t k = 0; k < row.size(); ++k) out += (k ? "," : "") + row[k];
    out += "\n";
  }
  return out;
}

// TEXT without column COLUMN (its header cell and every row's).
std::string WithoutColumn(const std::string& text, const std::string& column) {
  std::istringstream in(text);
  std::vector<std::vector<std::string>> rows;
  for (std::string l; std::getline(in, l);) rows.push_back(SplitCsvLine(l));
  const auto c = std::find(rows[0].begin(), rows[0].end(), column) - rows[0].begin();
  std::string out;
  for (auto row : rows) {
    row.erase(row.begin() + c);
    for (std::size_t k = 0; k < row.size(); ++k) out += (k ? "," : "") + row[k];
    out += "\n";
  }
  return out;
}

TEST(ResultCsv, BadCyclesCsvIsAnErrorNamingTheFileLineAndColumn) {
  testing::TempDir dir;
  const std::string good = TwoJobs().Csv();
  const std::string file = (dir / "cycles.csv").string();
  auto error = [&](const std::string& text) {
    WriteFileAtomically(dir / "cycles.csv", text);
    return testing::ErrorOf([&] { ReadAll(dir / "cycles.csv"); });
  };
  std::vector<std::string> lines;  // of the good file: the header, job 0's three rows, job 1's
  {
    std::istringstream in(good);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  ASSERT_EQ(lines.size(), 5u);
  const std::size_t columns = SplitCsvLine(lines[0]).size();

  // A cell that is not a number, or not an integer where one is written.
  std::string e = error(WithCell(good, 3, "fy", "heavy"));
  EXPECT_NE(e.find(file + ":3: column fy: heavy is not a number"), std::string::npos) << e;
  e = error(WithCell(good, 2, "t", ""));
  EXPECT_NE(e.find(file + ":2: column t: empty cell, expected a number"), std::string::npos) << e;
  e = error(WithCell(good, 4, "level", "1.5"));
  EXPECT_NE(e.find(file + ":4: column level: 1.5 is not an integer"), std::string::npos) << e;
  e = error(WithCell(good, 5, "job", "first"));
  EXPECT_NE(e.find(file + ":5: column job: first is not an integer"), std::string::npos) << e;
  e = error(WithCell(good, 4, "q", "0.25 zero 1"));
  EXPECT_NE(e.find(file + ":4: column q: number 2: zero is not a number"), std::string::npos) << e;

  // A required column missing from the header; the orientation, with the reason it may be.
  e = error(WithoutColumn(good, "nodes"));
  EXPECT_NE(e.find(file + ": has no column 'nodes' in its header (line 1)"), std::string::npos) << e;
  e = error(WithoutColumn(good, "q_B"));
  EXPECT_NE(e.find(file + ": has no column 'q_B'"), std::string::npos) << e;
  e = error(WithoutColumn(good, "qx"));
  EXPECT_NE(e.find(file + ": has no orientation column qx"), std::string::npos) << e;

  // A row with a cell too many, or too few.
  e = error(lines[0] + "\n" + lines[1] + ",extra\n");
  EXPECT_NE(e.find(file + ":2: " + std::to_string(columns + 1) + " cells, the header (line 1) has " +
                   std::to_string(columns)),
            std::string::npos)
      << e;
  e = error(lines[0] + "\n" + lines[1] + "\n" + lines[2].substr(0, lines[2].rfind(',')) + "\n");
  EXPECT_NE(e.find(file + ":3: " + std::to_string(columns - 1) + " cells, the header (line 1) has " +
                   std::to_string(columns)),
            std::string::npos)
      << e;

  // Reduced coordinates whose number changes within a job's model: line 4 is job 0's first row
  // of the deformable model, line 5 job 1's (another job may have another r: it read above),
  // line 6 job 0's again.
  const std::string two_models = good + lines[3] + "\n";
  e = error(WithCell(two_models, 6, "q", "0.5 0.25"));
  EXPECT_NE(e.find(file + ":6: column q: 2 reduced coordinates, but the first row of job 0 model pointshell (line 4) "
                          "holds 3"),
            std::string::npos)
      << e;
  e = error(WithCell(two_models, 6, "q_B", ""));
  EXPECT_NE(e.find(file + ":6: column q_B: 0 reduced coordinates, but the first row of job 0 model pointshell (line 4) "
                          "holds 1"),
            std::string::npos)
      << e;

  // No header at all.
  e = error("");
  EXPECT_NE(e.find(file + ": is empty"), std::string::npos) << e;
}

}  // namespace
}  // namespace contactlab
