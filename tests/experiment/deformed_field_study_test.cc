// The deformed-field study (study: deformed-field): a small armadillo sweep writes field_error.csv
// and field_slice.csv with sane contents, more domains reduce the legs' mirroring, and bad
// configs fail naming the file and the key.
#include "experiment/studies/deformed_field/deformed_field_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "experiment/studies/contact/result_csv.h"
#include "experiment/study.h"
#include "csv_rows.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// The armadillo of data/scenes/armadillo-legs.yaml at small sizes (field 40, 10 cells, r = 6),
// legs pulled apart by 10% of its height.
std::string Config(const std::string& extra = "", const std::string& deformable_extra = "") {
  return R"(name: tiny-field
study: deformed-field
scene:
  bodies:
    - name: armadillo
      mesh: ")" + testing::TestMesh("armadillo.obj").string() + R"("
      scale: 0.2
      center: true
      role: field
      field: {resolution: 40}
      deformable: {model: linear, modes: 6, cells: 10, anchor: {box: [-0.1, 0.0, -0.1, 0.1, 0.11, 0.1]},
                   field: {proxies: 20, neighbours: 4})" + deformable_extra + R"(}
    - name: probe
      mesh: "sphere:0.01"
      role: pointshell
deformation:
  loads:
    - {at: [-0.0295, -0.078, -0.026], force: [-1, 0, 0]}
    - {at: [0.0427, -0.078, -0.018], force: [1, 0, 0]}
  max_displacement: 0.1
measure: {points: 300, timing_repeats: 2, slice: {axis: z, at: -0.02, resolution: 24, jobs: {domains: 2}}}
sweep: {domains: [1, 2]}
)" + extra;
}

ExperimentConfig Load(const TempDir& dir, const std::string& text) {
  std::ofstream(dir / "config.yaml") << text;
  return LoadExperimentConfig(dir / "config.yaml");
}

using testing::ReadCsvRows;

double Num(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end()) ADD_FAILURE() << "no column " << key;
  return it == row.end() ? NAN : std::stod(it->second);
}

TEST(DeformedFieldStudy, SmallSweepWritesSaneErrorAndSliceTables) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, Config());
  EXPECT_EQ(config.study, "deformed-field");
  ASSERT_EQ(ExpandJobs(config).size(), 2u);
  RunOptions o;
  o.out_dir = dir / "out";
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  const std::vector<FieldErrorRow> rows = RunDeformedFieldStudy(config, o);
  ASSERT_EQ(rows.size(), 2u);
  for (const std::string& f : FindStudy("deformed-field")->Files()) EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / f)) << f;

  const auto error = ReadCsvRows(dir / "out" / "field_error.csv");
  ASSERT_EQ(error.size(), 2u);
  for (std::size_t j = 0; j < error.size(); ++j) {
    const auto& r = error[j];
    EXPECT_EQ(r.at("experiment"), "tiny-field");
    EXPECT_EQ(Num(r, "job"), double(j));
    EXPECT_EQ(Num(r, "proxies"), 20);
    EXPECT_EQ(Num(r, "neighbours"), 4);
    EXPECT_EQ(Num(r, "domains"), double(j + 1));  // the sweep's value, as built
    EXPECT_EQ(Num(r, "points"), 300);
    EXPECT_EQ(Num(r, "r"), 6);
    for (const char* key : {"rms_cells", "max_cells", "mean_cells", "rms_m", "max_m", "false_inside_m3"}) {
      EXPECT_TRUE(std::isfinite(Num(r, key))) << key;
    }
    EXPECT_GT(Num(r, "rms_cells"), 0);
    EXPECT_LE(Num(r, "rms_cells"), Num(r, "max_cells"));
    EXPECT_LE(std::abs(Num(r, "mean_cells")), Num(r, "rms_cells") * (1 + 1e-4));
    EXPECT_NEAR(Num(r, "rms_m"), Num(r, "rms_cells") * Num(r, "cell_m"), 1e-3 * Num(r, "rms_m"));
    EXPECT_GE(Num(r, "false_inside_m3"), 0);
    EXPECT_GT(Num(r, "query_ns"), 0);
    EXPECT_GT(Num(r, "update_ns"), 0);
    EXPECT_GT(Num(r, "exact_ns"), 0);
    // The pose: the largest displacement is 10% of the body's size.
    EXPECT_NEAR(Num(r, "max_displacement_m"), 0.1 * Num(r, "body_size_m"), 2e-3 * Num(r, "body_size_m"));
    EXPECT_NEAR(Num(r, "body_size_m"), 0.2, 0.01);
  }
  EXPECT_EQ(rows[0].r, 6);
  EXPECT_LE(rows[0].rms, rows[0].max);

  // The slice: only the job with domains = 2, a full grid through the legs (inside and outside).
  const auto slice = ReadCsvRows(dir / "out" / "field_slice.csv");
  ASSERT_FALSE(slice.empty());
  int inside = 0, max_i = 0, max_j = 0;
  for (const auto& s : slice) {
    EXPECT_EQ(s.at("domains"), "2");
    EXPECT_EQ(Num(s, "job"), 1);
    EXPECT_DOUBLE_EQ(Num(s, "z"), -0.02);
    EXPECT_TRUE(std::isfinite(Num(s, "exact_m")));
    EXPECT_TRUE(std::isfinite(Num(s, "approx_m")));
    inside += Num(s, "exact_m") < 0;
    max_i = std::max(max_i, int(Num(s, "i")));
    max_j = std::max(max_j, int(Num(s, "j")));
  }
  EXPECT_EQ(std::size_t(max_i + 1) * std::size_t(max_j + 1), slice.size());
  EXPECT_EQ(std::max(max_i, max_j) + 1, 24);
  EXPECT_GT(inside, 10);
  EXPECT_LT(inside, int(slice.size()) - 10);
}

TEST(DeformedFieldStudy, SingleJobRunsMergeIntoTheWholeSweep) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, Config());
  RunOptions o;
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  for (int j : {0, 1}) {
    o.out_dir = dir / ("job-" + std::to_string(j));
    (void)RunDeformedFieldStudy(config, o, {j});
  }
  MergeResults({dir / "job-0", dir / "job-1"}, dir / "merged");
  const auto error = ReadCsvRows(dir / "merged" / "field_error.csv");
  ASSERT_EQ(error.size(), 2u);
  EXPECT_EQ(error[0].at("job"), "0");
  EXPECT_EQ(error[1].at("job"), "1");
  EXPECT_EQ(ReadCsvRows(dir / "merged" / "field_slice.csv").size(), ReadCsvRows(dir / "job-1" / "field_slice.csv").size());
  EXPECT_TRUE(ReadCsvRows(dir / "job-0" / "field_slice.csv").empty());  // the slice is job 1's only
  EXPECT_FALSE(std::filesystem::exists(dir / "merged" / "cycles.csv"));
}

TEST(DeformedFieldStudy, BadConfigsNameTheFileAndTheKey) {
  TempDir dir;
  auto expect_error = [&](const std::string& text, const std::string& key) {
    try {
      (void)Load(dir, text);
      ADD_FAILURE() << "no error for " << key;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("config.yaml"), std::string::npos) << msg;
      EXPECT_NE(msg.find(key), std::string::npos) << msg;
    }
  };
  std::string c = Config();
  expect_error(std::string(c).replace(c.find("max_displacement"), 16, "max_displacemnt"), "max_displacemnt");
  expect_error(Config("trajectory: {type: approach-press}\n"), "trajectory");
  expect_error(std::string(c).replace(c.find("jobs: {domains: 2}"), 18, "jobs: {proxies: 2}"), "proxies");
  expect_error(std::string(c).replace(c.find("force: [1, 0, 0]"), 16, "force: [0, 0, 0]"), "force");
  expect_error(std::string(c).replace(c.find("study: deformed-field"), 21, "study: deformed"), "study");
  // A rigid field body (and no sweep, which would create the deformable block it writes into).
  std::string rigid = c;
  const std::size_t d = rigid.find("      deformable:");
  rigid.replace(d, rigid.find("    - name: probe") - d, "");
  expect_error(rigid, "sweep.domains");  // sweeping a rigid body's domains
  rigid.replace(rigid.find(", jobs: {domains: 2}"), 20, "");
  rigid.replace(rigid.find("sweep: {domains: [1, 2]}"), 24, "");
  expect_error(rigid, "no deformable block");
  // A contact study with the field study's sections.
  expect_error("name: x\nscene: {}\ndeformation: {}\ntrajectory: {type: approach-press}\n", "deformation");
}

TEST(DeformedFieldStudy, ALoadOutsideTheBodyFailsNamingItsKey) {
  TempDir dir;
  std::string c = Config();
  c.replace(c.find("at: [0.0427, -0.078, -0.018]"), 28, "at: [0.0427, -0.078, -0.150]");
  const ExperimentConfig config = Load(dir, c);
  RunOptions o;
  o.out_dir = dir / "out";
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  try {
    (void)RunDeformedFieldStudy(config, o, {0});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("deformation.loads[1].at"), std::string::npos) << msg;
    EXPECT_NE(msg.find("outside body 'armadillo'"), std::string::npos) << msg;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "field_error.csv"));
}

}  // namespace
}  // namespace contactlab
