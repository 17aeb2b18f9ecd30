// The experiment runner's cycle loop: it records each cycle (reduced coordinates of a
// deformable body included) into storage allocated before the loop, guards the models'
// temporal coherence against the trajectory's speed as the haptic cycle does, and counts the
// queries a model refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include "allocation_counter.h"
#include "contact/model_registry.h"
#include "experiment/studies/contact/result_csv.h"
#include "experiment/studies/contact/contact_study.h"
#include "scene/trajectory.h"
#include "scene_fixtures.h"
#include "test_support.h"

namespace contactlab {
namespace {

using testing::TempDir;

RunOptions Quiet(const TempDir& dir) {
  RunOptions o;
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  return o;
}

// A small clamped beam (a deformable pointshell) pressed by a probe, both models of the paper
// (the linear one's name is too long for a string's inline buffer) and a reference; CYCLE is
// the scene's haptic cycle in seconds.
std::string BeamConfig(const std::string& cycle) {
  testing::BeamUnderProbe scene{.box_subdivisions = 2, .points = 256, .levels = 2, .beam_resolution = 24, .modes = 4,
                                .cells = 8, .E = 5.0e6, .probe_z = 0.0205, .probe_resolution = 24};
  scene.model = "{k_C: 1000, L: 10, cycle_seconds: " + cycle + "}";
  return "name: beam-alloc\n"
         "scene:\n" +
         scene.Yaml(2) +
         "models: [pointshell, pointshell-linear]\n"
         "moving_body: probe\n"
         "trajectory: {type: slide, direction: [0, 0, -1], depth: 0.003, length: 0.005, tangent: [1, 0, 0], "
         "duration: 0.1}\n"
         "reference: pointshell-linear\n"
         "reference_every: 3\n";
}

// Allocations made by one run of the config TEXT (written to DIR/NAME.yaml), and its result.
long AllocationsOfRun(const TempDir& dir, const std::string& name, const std::string& text, JobResult* result) {
  std::ofstream(dir / (name + ".yaml")) << text;
  const ExperimentConfig config = LoadExperimentConfig(dir / (name + ".yaml"));
  const Job job = ExpandJobs(config).at(0);
  const long before = testing::AllocationCount();
  *result = RunJob(config, job, Quiet(dir));
  return testing::AllocationCount() - before;
}

// The same trajectory at half the cycle runs twice the cycles; if recording a cycle (its row,
// the beam's q, its displacement, the reference, the metrics' inputs) allocated, the longer run
// would make more allocations. Both runs read the assets the first one cached.
TEST(RunnerCycles, RecordingACycleAllocatesNothing) {
  TempDir dir;
  JobResult warm, at_1ms, at_half_ms;
  AllocationsOfRun(dir, "warm", BeamConfig("0.001"), &warm);  // builds and caches the assets
  const long n_1ms = AllocationsOfRun(dir, "a", BeamConfig("0.001"), &at_1ms);
  const long n_half_ms = AllocationsOfRun(dir, "b", BeamConfig("0.0005"), &at_half_ms);
  ASSERT_EQ(at_1ms.cycles.size(), 2u * 101);
  ASSERT_EQ(at_half_ms.cycles.size(), 2u * 201);
  // The beam deformed and its coordinates were recorded in every row.
  double deflection = 0;
  for (const CycleRow& row : at_half_ms.cycles) {
    ASSERT_EQ(row.q.size(), 4u);
    EXPECT_TRUE(row.q_B.empty());
    deflection = std::max(deflection, row.max_displacement);
  }
  EXPECT_GT(deflection, 1e-5);
  EXPECT_EQ(at_half_ms.cycles.back().model, "pointshell-linear");
  EXPECT_EQ(n_half_ms, n_1ms) << "cycles: " << at_1ms.cycles.size() << " and " << at_half_ms.cycles.size();
}

// A row's recorded coordinates print as they did when rows held them as text: %.9g, separated by
// spaces, in the q column; empty for a rigid body.
TEST(RunnerCycles, RecordedCoordinatesPrintWithNineSignificantDigits) {
  ExperimentConfig config;
  config.name = "exp";
  JobResult r;
  const double q[3] = {1.0 / 3.0, -2.5e-7, 12345.678901234};
  CycleRow row;
  row.model = "pointshell";
  row.deformable = true;
  row.q = q;
  r.cycles = {row};
  std::string text = CyclesCsvHeader(config);
  AppendCyclesCsv(config, r, &text);
  const std::vector<std::string> header = SplitCsvLine(text.substr(0, text.find('\n')));
  const std::size_t first = text.find('\n') + 1;
  const std::vector<std::string> cells = SplitCsvLine(text.substr(first, text.find('\n', first) - first));
  const auto col = [&](const std::string& name) { return std::size_t(std::find(header.begin(), header.end(), name) - header.begin()); };
  EXPECT_EQ(cells.at(col("q")), "0.333333333 -2.5e-07 12345.6789");
  EXPECT_EQ(cells.at(col("q_B")), "");
}

// The ball of a small ball-on-plate scene twists while pressed into the plate (it turns about
// the vertical through its centre, so its points move with the twist).
std::string TwistConfig(double max_point_speed, const std::string& models = "[pointshell]") {
  char speed[64];
  std::snprintf(speed, sizeof speed, "%.17g", max_point_speed);
  testing::BallOnPlate scene;
  scene.points = 1024;
  scene.levels = 3;
  scene.seed = 3;
  scene.k_C = 0;  // the model block below
  return "name: twist\nscene:\n" + scene.Yaml(2) + "  model: {k_C: 1000, L: 10, max_point_speed: " + speed +
         "}\n"
         "models: " +
         models +
         "\n"
         "moving_body: ball\n"
         "trajectory: {type: twist, direction: [0, 0, -1], depth: 0.002, angle: 0.6, duration: 0.2}\n"
         "sweep: {coherence: [false, true]}\n";
}

// The same trajectory as TwistConfig's, built here: the speed it puts on the ball's points.
double TwistPointSpeed() {
  ProceduralTrajectorySpec spec;
  spec.type = "twist";
  spec.direction = Eigen::Vector3d(0, 0, -1);
  spec.depth = 0.002;
  spec.angle = 0.6;
  spec.duration = 0.2;
  return MakeProceduralTrajectory(spec).MaxPointSpeed(0.02);  // the ball's radius
}

std::vector<JobResult> RunAll(const TempDir& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / (name + ".yaml")) << text;
  const ExperimentConfig config = LoadExperimentConfig(dir / (name + ".yaml"));
  std::vector<JobResult> results;
  for (const Job& job : ExpandJobs(config)) results.push_back(RunJob(config, job, Quiet(dir)));
  return results;
}

// A scene whose max_point_speed is below the trajectory's speed would let coherence sleep through
// contacts; the runner resets the model on every cycle that moves faster, so the coherent run
// renders exactly the contacts of the run without coherence. Set above the trajectory's speed
// (Trajectory::MaxPointSpeed, an independent finite difference of the same poses), nothing resets.
TEST(RunnerCycles, AMotionFasterThanMaxPointSpeedResetsCoherenceAndMissesNoContact) {
  TempDir dir;
  const double speed = TwistPointSpeed();
  ASSERT_GT(speed, 0.01);
  const std::vector<JobResult> slow = RunAll(dir, "slow", TwistConfig(0.2 * speed));
  ASSERT_EQ(slow.size(), 2u);
  const JobResult& off = slow[0];
  const JobResult& on = slow[1];
  ASSERT_EQ(off.cycles.size(), on.cycles.size());
  int touching = 0;
  for (std::size_t k = 0; k < off.cycles.size(); ++k) {
    ASSERT_EQ(on.cycles[k].contacts, off.cycles[k].contacts) << "cycle " << k;
    ASSERT_LT((on.cycles[k].force - off.cycles[k].force).norm(), 1e-9 * (1 + off.cycles[k].force.norm()))
        << "cycle " << k;
    touching += off.cycles[k].contacts > 0;
  }
  EXPECT_GT(touching, 100);
  EXPECT_GT(on.summary[0].coherence_resets, 100);
  EXPECT_EQ(on.summary[0].coherence_resets, off.summary[0].coherence_resets);  // the guard ignores the flag

  // Just above the trajectory's speed: no cycle resets; just below: some do.
  const std::vector<JobResult> fast_enough = RunAll(dir, "above", TwistConfig(1.01 * speed));
  EXPECT_EQ(fast_enough[1].summary[0].coherence_resets, 0);
  const std::vector<JobResult> too_slow = RunAll(dir, "below", TwistConfig(0.99 * speed));
  EXPECT_GT(too_slow[1].summary[0].coherence_resets, 0);
  // The count reaches summary.csv under the haptic loop's name.
  const ExperimentConfig config = LoadExperimentConfig(dir / "slow.yaml");
  std::string summary = SummaryCsvHeader(config);
  AppendSummaryCsv(config, on, &summary);
  const std::size_t first = summary.find('\n') + 1;
  const std::vector<std::string> header = SplitCsvLine(summary.substr(0, first - 1));
  const std::vector<std::string> row = SplitCsvLine(summary.substr(first, summary.find('\n', first) - first));
  const std::size_t c = std::find(header.begin(), header.end(), "coherence_resets") - header.begin();
  ASSERT_LT(c, header.size());
  EXPECT_EQ(row.at(c), std::to_string(on.summary[0].coherence_resets));
}

// A model that refuses every third query (as the paper's model refuses a deformation of the
// wrong size: no force, stats.faults = 1) and answers the others with a unit force.
class RefusingModel final : public ContactModel {
 public:
  std::string_view name() const override { return "test-refusing"; }
  ContactResult Evaluate(const ContactQuery& query) override {
    ContactResult r;
    if (query.cycle % 3 == 0) {
      r.stats.faults = 1;
    } else {
      r.on_B.force = Eigen::Vector3d(0, 0, 1);
    }
    return r;
  }
  void Reset() override {}
};

TEST(RunnerCycles, QueriesTheModelRefusesAreCountedAsContactFaults) {
  ContactModelEntry entry;
  entry.name = "test-refusing";
  entry.make = [](const ContactModelInputs&) -> std::unique_ptr<ContactModel> { return std::make_unique<RefusingModel>(); };
  RegisterContactModel(entry);
  TempDir dir;
  const std::vector<JobResult> runs = RunAll(dir, "refusing", TwistConfig(1.0, "[test-refusing, pointshell]"));
  const JobResult& r = runs.at(0);
  ASSERT_EQ(r.summary.size(), 2u);
  const std::int64_t cycles = r.summary[0].cycles;
  ASSERT_EQ(cycles, 201);
  EXPECT_EQ(r.summary[0].contact_faults, (cycles + 2) / 3);  // cycles 0, 3, 6, ...
  EXPECT_EQ(r.summary[1].contact_faults, 0);                 // the paper's model accepts every query
}

}  // namespace
}  // namespace contactlab
