// summary.csv's memory columns: the bytes of the field and pointshell each model reads, checked
// against counts made independently of the run (grid points of a freshly built field, the
// documented pointshell layout).
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "experiment/studies/contact/result_csv.h"
#include "experiment/studies/contact/contact_study.h"
#include "sdf/sparse_field.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"

namespace contactlab {
namespace {

using testing::TempDir;

TEST(BodyMemory, FieldBytesAreFourPerGridPoint) {
  const DistanceField field(Eigen::Vector3d::Zero(), 0.5, Eigen::Vector3i(3, 4, 5), std::vector<float>(60, 1.0f));
  EXPECT_EQ(field.memory_bytes(), 3 * 4 * 5 * 4);
  EXPECT_EQ(DistanceField().memory_bytes(), 0);
}

TEST(BodyMemory, SparseFieldBytesAreItsCoarseGridSlotsAndBricks) {
  // Two bricks along x, one stored: 3 x 2 x 2 coarse floats, 2 slots, 730 16-bit words.
  SparseFieldStorage s;
  s.bricks = Eigen::Vector3i(2, 1, 1);
  s.coarse.assign(12, 0.05f);
  s.slot = {0, SparseFieldStorage::kOutside};
  s.samples.assign(SparseFieldStorage::kBrickStride, 100);
  s.quantum = 1e-5f;
  s.band_voxels = 3;
  const DistanceField field(Eigen::Vector3d::Zero(), 0.01, std::move(s));
  EXPECT_EQ(field.memory_bytes(), 12 * 4 + 2 * 4 + 730 * 2);
  EXPECT_LT(field.memory_bytes(), 17 * 9 * 9 * 4);  // what the dense grid of its points would take
}

TEST(BodyMemory, PointshellBytesCountPointsNormalsAndTree) {
  // Two levels: 1 point, then 3 (the first point again plus two more); nodes 1 + 3.
  Pointshell p;
  p.x = p.y = p.z = p.nx = p.ny = p.nz = std::vector<float>(3, 0.0f);
  p.level_point_end = {1, 3};
  p.level_node_begin = {0, 1, 4};
  p.node_point = {0, 0, 1, 2};
  p.node_radius = {1.0f, 0, 0, 0};
  p.child_begin = {1, 4, 4, 4, 4};
  p.node_parent = {-1, 0, 0, 0};
  p.method = "a long description that is not counted";
  // 3 points x 6 floats, 2 + 3 level entries, 4 nodes x (point, radius, parent), 5 child ranges.
  EXPECT_EQ(p.memory_bytes(), 3 * 6 * 4 + (2 + 3) * 4 + 4 * 3 * 4 + 5 * 4);
}

// A 4 cm ball pressed into a plate, at two plate-field resolutions.
const std::string kConfig = [] {
  testing::BallOnPlate s;
  s.ball_z = 0.0215;
  s.points = 256;
  s.seed = 3;
  return "name: memory\nscene:\n" + s.Yaml(2);
}() + R"(models: [pointshell, pointshell-linear]
moving_body: ball
trajectory: {type: approach-press, direction: [0, 0, -1], approach: 0.002, depth: 0.003, duration: 0.01}
sweep:
  resolution: [24, 48]
)";

TEST(BodyMemory, SummaryRecordsTheFieldAndPointshellEachModelReads) {
  TempDir dir;
  std::ofstream(dir / "config.yaml") << kConfig;
  const ExperimentConfig config = LoadExperimentConfig(dir / "config.yaml");
  RunOptions options;
  options.out_dir = dir / "out";
  options.assets.cache_dir = dir / "cache";
  options.assets.verbose = false;
  options.progress = false;
  const std::vector<SummaryRow> rows = RunExperiment(config, options);
  ASSERT_EQ(rows.size(), 4u);  // 2 jobs x 2 models

  std::int64_t field_bytes[2] = {0, 0};
  for (int j = 0; j < 2; ++j) {
    // The job's bodies built afresh, without the cache the run filled.
    AssetOptions fresh;
    fresh.use_cache = false;
    fresh.verbose = false;
    SceneAssets assets(ExpandJobs(config)[j].scene, fresh);
    const Eigen::Vector3i dims = assets.B.field()->dims();
    field_bytes[j] = std::int64_t(dims.x()) * dims.y() * dims.z() * 4;
    const Pointshell& p = *assets.A.pointshell();
    const std::int64_t P = p.num_points(), N = p.num_nodes(), L = p.num_levels();
    ASSERT_EQ(P, 256);
    const std::int64_t pointshell_bytes = 6 * 4 * P + 4 * (L + L + 1) + 3 * 4 * N + 4 * (N + 1);
    for (const SummaryRow& r : rows) {
      if (r.job != j) continue;
      EXPECT_EQ(r.field_B_bytes, field_bytes[j]) << r.model << " job " << j;
      EXPECT_EQ(r.pointshell_A_bytes, pointshell_bytes) << r.model << " job " << j;
    }
  }
  // Twice the resolution, about eight times the samples (the padding adds a cell or two).
  const double ratio = double(field_bytes[1]) / double(field_bytes[0]);
  EXPECT_GT(ratio, 6.0);
  EXPECT_LT(ratio, 9.0);

  // summary.csv: the bytes as integers (result_csv_test: empty cells for a model that does not
  // read them).
  std::istringstream in(ReadWholeFile(dir / "out" / "summary.csv"));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = SplitCsvLine(line);
  const auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return std::size_t(it - header.begin());
  };
  int rows_seen = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = SplitCsvLine(line);
    ASSERT_EQ(cells.size(), header.size());
    const int job = std::stoi(cells[col("job")]);
    EXPECT_EQ(std::stoll(cells[col("field_B_bytes")]), field_bytes[job]);
    EXPECT_EQ(cells[col("pointshell_A_bytes")], std::to_string(rows[std::size_t(rows_seen)].pointshell_A_bytes));
    ++rows_seen;
  }
  EXPECT_EQ(rows_seen, 4);
}

}  // namespace
}  // namespace contactlab
