#include "experiment/studies/contact/contact_study.h"
#include "experiment/studies/contact/result_csv.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// A 4 cm ball pressed 1.5 mm into a plate: procedural, small, fast.
testing::BallOnPlate TinyBallPlate() {
  testing::BallOnPlate s;
  s.ball_z = 0.0215;
  s.points = 256;
  s.seed = 3;
  return s;
}
const std::string kConfig = "name: tiny\ndescription: a ball pressed into a plate\nscene:\n" +
                            TinyBallPlate().Yaml(2) + R"(models: [pointshell, pointshell-linear]
moving_body: ball
trajectory: {type: approach-press, direction: [0, 0, -1], approach: 0.002, depth: 0.003, duration: 0.04}
reference: pointshell-linear
reference_every: 2
sweep:
  points: [64, 256]
)";

ExperimentConfig Load(const TempDir& dir, const std::string& text, std::vector<std::string> overrides = {}) {
  std::ofstream(dir / "config.yaml") << text;
  return LoadExperimentConfig(dir / "config.yaml", overrides);
}

std::vector<std::string> Lines(const std::filesystem::path& file) {
  std::istringstream in(ReadWholeFile(file));
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

RunOptions Options(const TempDir& dir, const std::string& out) {
  RunOptions o;
  o.out_dir = dir / out;
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  o.parallel_jobs = 2;
  return o;
}

TEST(Runner, SmallSweepWritesLongFormatCsvAndMeta) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, kConfig);
  ASSERT_EQ(ExpandJobs(config).size(), 2u);
  const std::vector<SummaryRow> rows = RunExperiment(config, Options(dir, "out"));
  ASSERT_EQ(rows.size(), 4u);  // 2 jobs x 2 models
  const auto cycles = Lines(dir / "out" / "cycles.csv");
  EXPECT_EQ(cycles.front(),
            "experiment,job,points,model,cycle,t,x,y,z,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,nodes,level,max_penetration,"
            "depth_voxels,contact_area,patches,degraded,time_us,ref_fx,ref_fy,ref_fz,step_us,step_B_us,elastic_energy_J,kinetic_energy_J,"
            "max_displacement,q,q_B");
  EXPECT_EQ(cycles.size(), 1u + 2 * 2 * 41);  // header + jobs x models x cycles (0.04 s at 1 kHz)
  // The tree and the linear traversal of the deepest level agree; the linear model is its own
  // reference, so its error is zero.
  for (const SummaryRow& r : rows) {
    EXPECT_GT(r.max_force, 0.1) << r.model << " never touched";
    if (r.model == "pointshell-linear") {
      EXPECT_EQ(r.rms_rel_error, 0.0);
    } else {
      EXPECT_LT(r.rms_rel_error, 1e-6);
    }
  }
  // The ball is pushed up (+z) by the plate.
  const SummaryRow& r = rows.front();
  EXPECT_EQ(r.points, 64);
  const auto meta = nlohmann::json::parse(ReadWholeFile(dir / "out" / "meta.json"));
  EXPECT_EQ(meta["experiment"], "tiny");
  EXPECT_NE(meta["resolved_config"].get<std::string>().find("approach-press"), std::string::npos);
  for (const char* key : {"git_commit", "compiler", "compiler_flags", "cpu", "library_versions", "wall_seconds"}) {
    EXPECT_TRUE(meta.contains(key)) << key;
  }
  EXPECT_EQ(Lines(dir / "out" / "summary.csv").size(), 5u);
  EXPECT_EQ(Lines(dir / "out" / "convergence.csv").size(), 3u);  // header + one group per model
}

TEST(Runner, ForceOnTheMovingBallPointsUpAtTheDeepestCycle) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, kConfig, {"sweep.points=[256]", "models=[pointshell]"});
  const JobResult r = RunJob(config, ExpandJobs(config).front(), Options(dir, "out"));
  const CycleRow& deepest = r.cycles[20];  // halfway: 3 mm past the start
  EXPECT_GT(deepest.force.z(), 0.0);
  EXPECT_LT(deepest.force.head<2>().norm(), 0.05 * deepest.force.z());
  EXPECT_GT(deepest.contacts, 0);
  EXPECT_EQ(r.cycles.front().contacts, 0);  // starts 2 mm above the contact
}

// The reference runs at its most detail as its registry entry declares it (the paper's model:
// its deepest level), whatever level the scene gives the models compared: the reference force is
// the force of the same model run at its deepest level, not the coarse one compared.
TEST(Runner, TheReferenceRunsAtItsDeepestLevelWhateverTheSceneSays) {
  TempDir dir;
  const std::vector<std::string> common = {"sweep.points=[256]", "models=[pointshell-linear]", "reference_every=1"};
  std::vector<std::string> coarse = common;
  coarse.push_back("scene.model.level=0");
  const ExperimentConfig shallow = Load(dir, kConfig, coarse);
  const JobResult r = RunJob(shallow, ExpandJobs(shallow).front(), Options(dir, "out"));
  const ExperimentConfig deep = Load(dir, kConfig, common);
  const JobResult d = RunJob(deep, ExpandJobs(deep).front(), Options(dir, "deep"));
  ASSERT_EQ(r.cycles.size(), d.cycles.size());
  double apart = 0;  // how far the coarse level's force is from the deepest one's
  for (std::size_t k = 0; k < r.cycles.size(); ++k) {
    ASSERT_TRUE(r.cycles[k].has_reference) << k;
    EXPECT_LT((r.cycles[k].reference_force - d.cycles[k].force).norm(), 1e-9 * (1 + d.cycles[k].force.norm())) << k;
    apart = std::max(apart, (r.cycles[k].force - d.cycles[k].force).norm());
  }
  EXPECT_GT(apart, 0.01) << "level 0 renders another force than the deepest level";
}

TEST(Runner, SingleJobsMergeIntoTheFullRun) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, kConfig);
  RunExperiment(config, Options(dir, "job0"), {0});
  RunExperiment(config, Options(dir, "job1"), {1});
  MergeResults({dir / "job0", dir / "job1"}, dir / "merged");
  EXPECT_EQ(Lines(dir / "merged" / "cycles.csv").size(), 1u + 2 * 2 * 41);
  EXPECT_EQ(Lines(dir / "merged" / "summary.csv").size(), 5u);
  EXPECT_THROW(MergeResults({dir / "job0", dir / "nowhere"}, dir / "merged2"), Error);
  EXPECT_THROW(RunExperiment(config, Options(dir, "bad"), {7}), Error);
}

TEST(Runner, AFailedRunLeavesNoResultFile) {
  TempDir dir;
  // The second sweep point names a model that does not exist (put in after loading, which
  // refuses the name): the run fails after the first job has finished, and no output file may
  // exist.
  ExperimentConfig config = Load(dir, kConfig, {"sweep.model=[pointshell, pointshell-linear]", "sweep.points=[64]"});
  bool replaced = false;
  for (SweepAxis& axis : config.sweep) {
    if (axis.name == "model") axis.values[1] = "no-such-model", replaced = true;
  }
  ASSERT_TRUE(replaced);
  EXPECT_THROW(RunExperiment(config, Options(dir, "out")), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "cycles.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "summary.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "meta.json"));
}

std::string ConfigError(const std::string& text, std::vector<std::string> overrides = {}) {
  TempDir dir;
  try {
    Load(dir, text, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Runner, ConfigErrorsNameTheFileAndKey) {
  std::string e = ConfigError(Replace(kConfig, "reference_every: 2", "reference_evry: 2"));
  EXPECT_NE(e.find("config.yaml:22"), std::string::npos) << e;
  EXPECT_NE(e.find("reference_evry"), std::string::npos) << e;
  e = ConfigError(Replace(kConfig, "points: [64, 256]", "pionts: [64, 256]"));
  EXPECT_NE(e.find("sweep.pionts"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown sweep axis"), std::string::npos) << e;
  e = ConfigError(Replace(kConfig, "points: [64, 256]", "points: [64, many]"));
  EXPECT_NE(e.find("sweep.points value 'many'"), std::string::npos) << e;
  e = ConfigError(Replace(kConfig, "type: approach-press", "type: wiggle"));
  EXPECT_NE(e.find("trajectory.type"), std::string::npos) << e;
  e = ConfigError(Replace(kConfig, "moving_body: ball", "moving_body: hammer"));
  EXPECT_NE(e.find("moving_body"), std::string::npos) << e;
  e = ConfigError(kConfig, {"trajectory.duration=-1"});
  EXPECT_NE(e.find("trajectory.duration"), std::string::npos) << e;
  e = ConfigError(kConfig, {"no-equals-sign"});
  EXPECT_NE(e.find("key.path=value"), std::string::npos) << e;
}

TEST(Runner, RoleReversalKeepsTheForceOnTheSameBody) {
  TempDir dir;
  std::string text = Replace(kConfig, "pointshell: {points: 256, levels: 2, seed: 3}",
                             "pointshell: {points: 4096, levels: 2, seed: 3, offset: 0}");
  text = Replace(text, "      role: field\n", "      role: field\n      pointshell: {points: 4096, levels: 2, seed: 3, offset: 0}\n");
  const ExperimentConfig config =
      Load(dir, text, {"sweep.points=[4096]", "sweep.roles=[normal, swapped]", "models=[pointshell-linear]", "reference="});
  const std::vector<Job> jobs = ExpandJobs(config);
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[1].scene.pointshell_body.name, "plate");
  const JobResult a = RunJob(config, jobs[0], Options(dir, "a"));
  const JobResult b = RunJob(config, jobs[1], Options(dir, "b"));
  // Both report the force on the moving ball, each matching the eq. (2) limit of its own
  // roles at the deepest cycle (pointshells on the surface, offset 0; enough points in contact
  // that the L/l rule holds). Ball R as pointshell, centre H above the plate:
  //   |F| = k_C L R (R/3 - H/2 + H^3/(6 R^2)) / (R - H)   (mean depth over the submerged cap).
  // Plate as pointshell: the mean of d = sqrt(rho^2 + H^2) - R over the disk rho < a,
  // a^2 = R^2 - H^2, inside the ball: |F| = k_C L (R - 2 (R^3 - H^3) / (3 a^2)).
  const double R = 0.02, kC = 1000, L = 10;
  for (const JobResult* r : {&a, &b}) {
    const CycleRow* deepest = &r->cycles.front();
    for (const CycleRow& c : r->cycles) {
      if (c.position.z() < deepest->position.z()) deepest = &c;
    }
    const double H = deepest->position.z();  // the plate's top is z = 0
    ASSERT_NEAR(H, 0.0185, 1e-9);
    const double a2 = R * R - H * H;
    const double limit = r == &a ? kC * L * R * (R / 3 - H / 2 + H * H * H / (6 * R * R)) / (R - H)
                                 : kC * L * (R - 2 * (R * R * R - H * H * H) / (3 * a2));
    // Measured: 4 % (ball, 150 points in contact) and 1 % (plate, 15 points) from the limit.
    EXPECT_NEAR(deepest->force.z(), limit, 0.06 * limit) << (r == &a ? "ball" : "plate") << " as the pointshell";
    EXPECT_LT(deepest->force.head<2>().norm(), 0.05 * limit);
    EXPECT_GE(deepest->contacts, 10);
  }
}

}  // namespace
}  // namespace contactlab

namespace contactlab {
namespace {

TEST(Runner, ProfilesApplyNamedOverrides) {
  TempDir dir;
  const std::string text = std::string(kConfig) + "profiles:\n  small: {sweep.points: [64], trajectory.duration: 0.01}\n";
  const ExperimentConfig config = [&] {
    std::ofstream(dir / "config.yaml") << text;
    return LoadExperimentConfig(dir / "config.yaml", {}, "small");
  }();
  ASSERT_EQ(ExpandJobs(config).size(), 1u);
  EXPECT_EQ(ExpandJobs(config).front().scene.pointshell_body.pointshell.points, 64);
  EXPECT_THROW(LoadExperimentConfig(dir / "config.yaml", {}, "huge"), Error);
}

TEST(Runner, TouchPlacesTheMovingBodyAtFirstContactTowardTheOtherBody) {
  TempDir dir;
  // The ball starts 5 cm above the plate; touch moves it down ("toward" the plate) until it is
  // 0.1 mm deep, then the trajectory approaches from 2 mm above and presses 3 mm past that.
  std::string text = Replace(kConfig, "[0, 0, 0.0215, 1, 0, 0, 0]", "[0.001, 0.002, 0.07, 1, 0, 0, 0]");
  text = Replace(text, "direction: [0, 0, -1]", "direction: toward, touch: true, touch_depth: 0.0001");
  const ExperimentConfig config = Load(dir, text, {"sweep.points=[256]", "models=[pointshell-linear]", "reference="});
  const JobResult r = RunJob(config, ExpandJobs(config).front(), Options(dir, "out"));
  EXPECT_EQ(r.cycles.front().contacts, 0);
  const CycleRow& deepest = r.cycles[20];
  EXPECT_NEAR(deepest.max_penetration, 0.0031, 0.0004);
  EXPECT_GT(deepest.force.z(), 0);
}

// Role reversal compares one motion: the swapped job takes the touch placement of the job in
// the config's role order. Each order alone would place the ball differently: the plate as the
// pointshell sits on its own offset surface (half of its 5 mm voxels) instead of the ball's
// (half of 2 mm), so the ball would stop about 1.5 mm higher.
TEST(Runner, SwappedRolesFollowThePlacementOfTheConfigsRoleOrder) {
  TempDir dir;
  std::string text = Replace(kConfig, "[0, 0, 0.0215, 1, 0, 0, 0]", "[0.001, 0.002, 0.07, 1, 0, 0, 0]");
  text = Replace(text, "direction: [0, 0, -1]", "direction: toward, touch: true, touch_depth: 0.0001");
  text = Replace(text, "      role: field\n", "      role: field\n      pointshell: {points: 256, levels: 2, seed: 3}\n");
  const ExperimentConfig config =
      Load(dir, text, {"sweep.points=[256]", "sweep.roles=[normal, swapped]", "models=[pointshell-linear]", "reference="});
  const std::vector<Job> jobs = ExpandJobs(config);
  ASSERT_EQ(jobs.size(), 2u);
  ASSERT_TRUE(jobs[1].roles_swapped);
  const JobResult a = RunJob(config, jobs[0], Options(dir, "a"));
  const JobResult b = RunJob(config, jobs[1], Options(dir, "b"));
  ASSERT_EQ(a.cycles.size(), b.cycles.size());
  for (std::size_t k = 0; k < a.cycles.size(); ++k) {
    ASSERT_EQ(a.cycles[k].position, b.cycles[k].position) << "cycle " << k;
  }
  // The swapped job placed on its own would differ: its touch pose is another one.
  Job alone = jobs[1];
  alone.roles_swapped = false;
  const JobResult c = RunJob(config, alone, Options(dir, "c"));
  EXPECT_GT((c.cycles.front().position - b.cycles.front().position).norm(), 5e-4);
}

TEST(Runner, SceneAxisRunsEachJobOnItsOwnScene) {
  TempDir dir;
  std::ofstream(dir / "other.yaml") << R"(name: other
bodies:
  - {name: cube, mesh: "box:0.02,0.02,0.02,2", role: pointshell, pose: [0, 0, 0.05, 1, 0, 0, 0],
     pointshell: {points: 256, levels: 2}, field: {resolution: 24}}
  - {name: slab, mesh: "box:0.05,0.05,0.01,2", role: field, pose: [0, 0, -0.01, 1, 0, 0, 0],
     field: {resolution: 24}}
)";
  std::string text = Replace(kConfig, "moving_body: ball\n", "");
  text = Replace(text, "direction: [0, 0, -1]", "direction: toward, touch: true");
  const ExperimentConfig config =
      Load(dir, text, {"sweep.points=[256]", "reference=", "sweep.scene=[" + (dir / "other.yaml").string() + "]"});
  const std::vector<Job> jobs = ExpandJobs(config);
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].scene.pointshell_body.name, "cube");
  EXPECT_EQ(jobs[0].moving_body, "slab");  // the job scene's field body
  const JobResult r = RunJob(config, jobs[0], Options(dir, "out"));
  EXPECT_LT(r.cycles[20].force.z(), 0);  // the slab is pushed down by the cube
}

// A comma or a quote in the experiment's name and in a swept scene path: each stays one cell
// (RFC 4180 quoting, spelled out here), so the single-job folders merge as complete and the
// rows read back with every value in its column.
TEST(Runner, CommaOrQuoteInTheNameOrASweptScenePathStaysOneCellAndMerges) {
  TempDir dir;
  const std::string one = (dir / "plate, \"one\".yaml").string(), two = (dir / "plate,two.yaml").string();
  for (const std::string& file : {one, two}) std::ofstream(file) << TinyBallPlate().Yaml();
  const std::string text = Replace(Replace(kConfig, "name: tiny", "name: 'tiny, \"quoted\"'"), "reference_every: 2\n", "");
  const ExperimentConfig config =
      Load(dir, text, {"models=[pointshell]", "reference=", "sweep.points=[64]", "sweep.scene=['" + one + "', '" + two + "']"});
  RunExperiment(config, Options(dir, "job0"), {0});
  RunExperiment(config, Options(dir, "job1"), {1});
  MergeResults({dir / "job0", dir / "job1"}, dir / "merged");

  auto quoted = [](const std::string& s) {  // RFC 4180: enclosed in quotes, inner quotes doubled
    std::string q = "\"";
    for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  const auto summary = Lines(dir / "merged" / "summary.csv");
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[0].rfind("experiment,job,sweep.points,scene,model,", 0), 0u) << summary[0];
  EXPECT_EQ(summary[1].rfind(quoted("tiny, \"quoted\"") + ",0,64," + quoted(one) + ",pointshell,", 0), 0u) << summary[1];
  EXPECT_EQ(summary[2].rfind(quoted("tiny, \"quoted\"") + ",1,64," + quoted(two) + ",pointshell,", 0), 0u) << summary[2];
  std::vector<CyclesCsvRow> rows;
  const std::vector<std::string> axes = ReadCyclesCsv(dir / "merged" / "cycles.csv", [&](const CyclesCsvRow& r) {
    rows.push_back(r);
  });
  EXPECT_EQ(axes, (std::vector<std::string>{"points", "scene"}));
  ASSERT_EQ(rows.size(), 2u * 41);
  EXPECT_EQ(rows.front().experiment, "tiny, \"quoted\"");
  EXPECT_EQ(rows.front().axis_values, (std::vector<std::string>{"64", one}));
  EXPECT_EQ(rows.back().axis_values, (std::vector<std::string>{"64", two}));
  EXPECT_EQ(rows.back().model, "pointshell");
}

}  // namespace
}  // namespace contactlab
