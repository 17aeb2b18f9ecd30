// The many-bodies study (study: many-bodies): a ball slid along a floor and a wall among far
// boxes writes the wrench on the tool that two-body contact studies of each pair give apart,
// culls the far boxes, records per pair what it was handed of one budget, and bad configs fail
// naming the file and the key.
#include "experiment/studies/many_bodies/many_bodies_study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "csv_rows.h"
#include "experiment/studies/contact/contact_study.h"
#include "experiment/study.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::ReadCsvRows;
using testing::TempDir;

// The bodies: a ball (the tool; 0.5 mm into the floor and 0.5 mm into the wall at its start),
// the floor and the wall (fields), and FAR small boxes 0.2 m off.
std::string Ball() {
  return "    - name: ball\n"
         "      mesh: \"sphere:0.02,3\"\n"
         "      pose: [0, 0, 0.0195, 1, 0, 0, 0]\n"
         "      role: pointshell\n"
         "      pointshell: {points: 512, levels: 3, seed: 2}\n"
         "      field: {resolution: 24}\n";
}
std::string Floor() {
  return "    - {name: floor, mesh: \"box:0.04,0.06,0.01,2\", pose: [0, 0, -0.01, 1, 0, 0, 0], role: field,\n"
         "       field: {resolution: 24}}\n";
}
std::string Wall() {
  return "    - {name: wall, mesh: \"box:0.01,0.06,0.04,2\", pose: [0.0295, 0, 0.0395, 1, 0, 0, 0], role: field,\n"
         "       field: {resolution: 24}}\n";
}
std::string Far(int n) {
  std::ostringstream os;
  for (int i = 0; i < n; ++i) {
    os << "    - {name: far" << i << ", mesh: \"box:0.01,0.01,0.01,1\", pose: [" << 0.05 * i
       << ", 0.2, 0, 1, 0, 0, 0], role: field, field: {resolution: 16}}\n";
  }
  return os.str();
}
const char* kModel = "  model: {k_C: 1000, L: 0, max_point_speed: 0.5}\n";
const char* kTrajectory =
    "trajectory: {type: slide, direction: [0, 0, -1], depth: 0.0005, tangent: [0, 1, 0], length: 0.02, duration: 0.3}\n";

std::string WorldConfig(const std::string& extra = "", const std::string& scene_extra = "") {
  return "name: ball-among-plates\nstudy: many-bodies\nmodels: [pointshell]\nscene:\n  tool: ball\n  bodies:\n" + Ball() +
         Floor() + Wall() + Far(3) + kModel + scene_extra + kTrajectory + extra;
}

std::string TwoBodyConfig(const std::string& other) {
  return "name: ball-and-one\nmodels: [pointshell]\nmoving_body: ball\nscene:\n  bodies:\n" + Ball() + other + kModel +
         kTrajectory;
}

ExperimentConfig Load(const TempDir& dir, const std::string& text, const std::string& name = "config.yaml") {
  std::ofstream(dir / name) << text;
  return LoadExperimentConfig(dir / name);
}

RunOptions Options(const TempDir& dir, const std::string& out) {
  RunOptions o;
  o.out_dir = dir / out;
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  return o;
}

double Num(const std::map<std::string, std::string>& row, const std::string& key) {
  const auto it = row.find(key);
  if (it == row.end()) ADD_FAILURE() << "no column " << key;
  return it == row.end() ? NAN : std::stod(it->second);
}

Eigen::Vector3d Force(const std::map<std::string, std::string>& row) {
  return {Num(row, "fx"), Num(row, "fy"), Num(row, "fz")};
}

std::string LoadError(const TempDir& dir, const std::string& text) {
  return testing::ErrorOf([&] { (void)Load(dir, text, "bad.yaml"); });
}

TEST(ManyBodiesStudy, TheToolsForceIsWhatTwoBodyStudiesOfEachPairGiveApart) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, WorldConfig());
  EXPECT_EQ(config.study, "many-bodies");
  EXPECT_EQ(config.moving_body, "ball") << "the tool moves";
  const std::vector<WorldJobResult> results = RunWorldStudy(config, Options(dir, "out"));
  ASSERT_EQ(results.size(), 1u);
  for (const std::string& f : FindStudy("many-bodies")->Files()) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / f)) << f;
  }
  const auto cycles = ReadCsvRows(dir / "out" / "world_cycles.csv");
  ASSERT_EQ(cycles.size(), 301u);  // 0.3 s at 1 kHz, both ends

  // The same trajectory through two-body contact studies: the ball against the floor alone,
  // then against the wall alone; the tool's force is their sum, cycle by cycle.
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(301, 3);
  std::vector<int> touching(301, 0);  // the two-body studies with contact, per cycle
  for (const std::string& other : {Floor(), Wall()}) {
    const std::string out = other == Floor() ? "floor" : "wall";
    (void)RunExperiment(Load(dir, TwoBodyConfig(other), out + ".yaml"), Options(dir, out));
    const auto two = ReadCsvRows(dir / out / "cycles.csv");
    ASSERT_EQ(two.size(), 301u) << out;
    for (int k = 0; k < 301; ++k) {
      sum.row(k) += Force(two[std::size_t(k)]).transpose();
      touching[std::size_t(k)] += Num(two[std::size_t(k)], "contacts") > 0;
    }
  }
  double largest = 0;
  for (int k = 0; k < 301; ++k) {
    const auto& r = cycles[std::size_t(k)];
    EXPECT_EQ(Num(r, "cycle"), k);
    const Eigen::Vector3d expected = sum.row(k).transpose();
    largest = std::max(largest, expected.norm());
    EXPECT_LT((Force(r) - expected).norm(), 1e-4 * expected.norm() + 1e-9) << "cycle " << k;
    EXPECT_EQ(Num(r, "pairs_near"), 2) << "the far boxes are culled, cycle " << k;
    EXPECT_EQ(Num(r, "pairs_touching"), touching[std::size_t(k)]) << "cycle " << k;
  }
  EXPECT_GT(largest, 1.0);
  EXPECT_EQ(*std::max_element(touching.begin(), touching.end()), 2) << "the ball pressed into both at once";

  // One row per near pair per cycle, in the pair's A/B order: the ball (pointshell) is A.
  const auto pairs = ReadCsvRows(dir / "out" / "world_pairs.csv");
  ASSERT_EQ(pairs.size(), 2u * 301u);
  std::set<std::string> seen;
  for (const auto& r : pairs) {
    EXPECT_EQ(r.at("body_a"), "ball");
    seen.insert(r.at("body_b"));
    EXPECT_EQ(r.at("pair_model"), "pointshell");
    EXPECT_EQ(Num(r, "node_budget"), 0) << "no budget: unlimited";
  }
  EXPECT_EQ(seen, (std::set<std::string>{"floor", "wall"}));
  EXPECT_TRUE(ReadCsvRows(dir / "out" / "world_bodies.csv").empty()) << "no deformable body";
  const auto summary = ReadCsvRows(dir / "out" / "world_summary.csv");
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(Num(summary[0], "bodies"), 6);
  EXPECT_EQ(Num(summary[0], "pairs"), 5);
  EXPECT_EQ(Num(summary[0], "max_pairs_touching"), 2);
  EXPECT_NEAR(Num(summary[0], "max_force_N"), largest, 1e-3 * largest);
}

TEST(ManyBodiesStudy, ASweptBudgetIsSharedByThePairsNearInACycle) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, WorldConfig("sweep: {node_budget: [0, 40]}\n"));
  ASSERT_EQ(JobCount(config), 2u);
  (void)RunWorldStudy(config, Options(dir, "out"));
  const auto pairs = ReadCsvRows(dir / "out" / "world_pairs.csv");
  double handed_40 = 0;
  int rows_40 = 0, degraded_0 = 0, degraded_40 = 0;
  for (const auto& r : pairs) {
    if (Num(r, "job") == 0) {
      EXPECT_EQ(Num(r, "node_budget"), 0);
      degraded_0 += Num(r, "degraded") > 0;
      continue;
    }
    ++rows_40;
    handed_40 += Num(r, "node_budget");
    degraded_40 += Num(r, "degraded") > 0;
    EXPECT_GE(Num(r, "node_budget"), 20) << "never less than an equal share of the two";
  }
  ASSERT_EQ(rows_40, 2 * 301);
  EXPECT_EQ(degraded_0, 0);
  EXPECT_GT(degraded_40, 0) << "40 nodes for two pairs of 512-point trees degrades them";
  EXPECT_GT(handed_40, 0);
}

TEST(ManyBodiesStudy, BadConfigsFailNamingTheFileAndKey) {
  TempDir dir;
  // A two-body study refuses a scene of many bodies, and this one a scene of two.
  std::string contact = WorldConfig();
  contact.replace(contact.find("study: many-bodies"), 18, "study: contact");
  std::string e = LoadError(dir, contact);
  EXPECT_NE(e.find("an experiment of study: contact takes a scene of two bodies"), std::string::npos) << e;
  std::string two = TwoBodyConfig(Floor());
  two.insert(two.find("models:"), "study: many-bodies\n");
  e = LoadError(dir, two);
  EXPECT_NE(e.find("bad.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("takes a scene of many bodies"), std::string::npos) << e;
  // Only the tool moves; a trajectory toward "the other body" or touching it has none.
  e = LoadError(dir, WorldConfig("moving_body: floor\n"));
  EXPECT_NE(e.find("moving_body"), std::string::npos) << e;
  EXPECT_NE(e.find("the tool moves: 'ball'"), std::string::npos) << e;
  std::string toward = WorldConfig();
  toward.replace(toward.find("direction: [0, 0, -1]"), 21, "direction: toward");
  e = LoadError(dir, toward);
  EXPECT_NE(e.find("bad.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("trajectory.direction"), std::string::npos) << e;
  EXPECT_NE(e.find("give the direction as a vector"), std::string::npos) << e;
  std::string touch = WorldConfig();
  touch.replace(touch.find("duration: 0.3}"), 14, "duration: 0.3, touch: true}");
  e = LoadError(dir, touch);
  EXPECT_NE(e.find("trajectory.touch"), std::string::npos) << e;
  // A pair's model that cannot take its bodies is refused at load.
  e = LoadError(dir, WorldConfig("", "  pairs:\n    - {bodies: [floor, wall]}\n"));
  EXPECT_NE(e.find("pairs[0]"), std::string::npos) << e;
  EXPECT_NE(e.find("neither of floor"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace contactlab
