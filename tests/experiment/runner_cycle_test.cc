// The experiment runner's cycle loop: it records each cycle (reduced coordinates of a
// deformable body included) into storage allocated before the loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include "allocation_counter.h"
#include "experiment/result_csv.h"
#include "experiment/runner.h"
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
  return "name: beam-alloc\n"
         "scene:\n"
         "  name: beam-probe\n"
         "  bodies:\n"
         "    - name: beam\n"
         "      mesh: \"box:0.1,0.01,0.01,2\"\n"
         "      role: pointshell\n"
         "      pointshell: {points: 256, levels: 2, seed: 1}\n"
         "      field: {resolution: 24}\n"
         "      deformable: {model: stvk, modes: 4, cells: 8, E: 5.0e6, nu: 0.3, rho: 1100,\n"
         "                   damping: {alpha: 8.0, beta: 0.0005}, anchor: {below: [x, -0.09]}}\n"
         "    - name: probe\n"
         "      mesh: \"sphere:0.01,2\"\n"
         "      pose: [0.07, 0, 0.0205, 1, 0, 0, 0]\n"
         "      role: field\n"
         "      field: {resolution: 24}\n"
         "  model: {k_C: 1000, L: 10, cycle_seconds: " +
         cycle +
         "}\n"
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

}  // namespace
}  // namespace contactlab
