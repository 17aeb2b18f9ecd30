// The contact study (`study: contact`, the default; experiment/runner.h): every model of a job
// follows the trajectory cycle by cycle; results cycles.csv, summary.csv and convergence.csv.
#include <cstdio>

#include "experiment/convergence_table.h"
#include "experiment/runner.h"
#include "experiment/study.h"
#include "experiment/trajectory.h"

namespace contactlab {
namespace {

// Every job's trajectory parses (a mapping with a known type and its keys), so errors come
// before any work.
void CheckContactStudy(const ExperimentConfig&, const ConfigNode&, const std::vector<Job>& jobs) {
  for (const Job& job : jobs) (void)ParseTrajectory(job.trajectory_node);
}

// Runs the jobs and prints one line per job and model.
void RunContactStudy(const ExperimentConfig& config, const RunOptions& options, const std::vector<int>& only) {
  const std::size_t total = ExpandJobs(config).size();
  std::fprintf(stderr, "experiment %s: %zu of %zu jobs, models:", config.name.c_str(),
               only.empty() ? total : only.size(), total);
  for (const auto& m : config.models) std::fprintf(stderr, " %s", m.c_str());
  std::fprintf(stderr, "\n");
  const std::vector<SummaryRow> rows = RunExperiment(config, options, only);
  std::printf("%-6s %-24s %-9s %10s %10s %10s %12s\n", "job", "model", "points", "max|F| N", "jump N", "p99 us",
              "rel.err");
  for (const SummaryRow& r : rows) {
    std::printf("%-6d %-24s %-9d %10.4g %10.4g %10.1f %12.4g\n", r.job, r.model.c_str(), r.points, r.max_force,
                r.max_jump, r.p99_us, r.rms_rel_error);
  }
}

}  // namespace

void RegisterContactStudy() {
  Study s;
  s.name = kContactStudy;
  s.description = "models compared along a trajectory";
  s.sections = {"models", "moving_body", "trajectory", "reference", "reference_every"};
  s.required = {"trajectory"};
  s.tables = {"cycles.csv", "summary.csv"};
  s.derived = {{"convergence.csv", [](const std::vector<std::string>& tables) { return ConvergenceCsv(tables[1]); }}};
  s.replayable = true;
  s.check = CheckContactStudy;
  s.run = RunContactStudy;
  s.reference = TrajectoryReference;
  RegisterStudy(std::move(s));
}

}  // namespace contactlab
