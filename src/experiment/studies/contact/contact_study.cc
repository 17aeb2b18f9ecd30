// The contact study (`study: contact`, the default; contact_study.h): every model of a job
// follows the trajectory cycle by cycle; results cycles.csv, summary.csv and convergence.csv.
#include "experiment/studies/contact/contact_study.h"

#include <cstdio>

#include "experiment/run_metadata.h"
#include "experiment/studies/contact/convergence_table.h"
#include "experiment/studies/contact/result_csv.h"
#include "experiment/study.h"
#include "scene/trajectory.h"
#include "util/error.h"

namespace contactlab {

std::vector<SummaryRow> RunExperiment(const ExperimentConfig& config, const RunOptions& options,
                                      const std::vector<int>& job_indices) {
  const Study& study = StudyOf(config);
  if (study.name != kContactStudy) {
    Fail(config.file, "is a " + config.study + " study (" + study.description + "), not a contact study");
  }
  std::vector<JobResult> results(job_indices.empty() ? JobCount(config) : job_indices.size());
  const JobsRun jobs = RunJobs(config, job_indices, options, [&](std::size_t i, const Job& job) {
    results[i] = RunJob(config, job, options);
  });
  const std::vector<int>& indices = jobs.indices;
  const double wall = jobs.wall_seconds;
  const int parallel = jobs.parallel;

  // Everything is formatted in memory and written at the end, each file atomically.
  std::string cycles = CyclesCsvHeader(config), summary = SummaryCsvHeader(config);
  std::vector<SummaryRow> rows;
  for (const JobResult& r : results) {
    AppendCyclesCsv(config, r, &cycles);
    AppendSummaryCsv(config, r, &summary);
    rows.insert(rows.end(), r.summary.begin(), r.summary.end());
  }
  WriteStudyResults(study, options.out_dir, {cycles, summary}, RunMetadata(config, indices, wall, parallel));
  return rows;
}

namespace {

// Runs the jobs and prints one line per job and model.
void RunContactStudy(const ExperimentConfig& config, const RunOptions& options, const std::vector<int>& only) {
  const std::size_t total = JobCount(config);
  std::fprintf(stderr, "experiment %s: %zu of %zu jobs, models:", config.name.c_str(),
               only.empty() ? total : only.size(), total);
  for (const auto& m : config.models) std::fprintf(stderr, " %s", m.c_str());
  std::fprintf(stderr, "\n");
  const std::vector<SummaryRow> rows = RunExperiment(config, options, only);
  // One block per job: its swept values, then a line per model ("-": no value, as an empty cell
  // of summary.csv).
  std::printf("%-6s %-24s %-9s %10s %10s %10s %12s\n", "job", "model", "points", "max|F| N", "jump N", "p99 us",
              "rel.err");
  int shown_job = -1;
  for (const SummaryRow& r : rows) {
    if (r.job != shown_job && !config.sweep.empty()) {
      std::printf("job %d: %s\n", r.job, JobLabel(config, std::size_t(r.job)).c_str());
    }
    shown_job = r.job;
    const std::string points = r.reads_pointshell() ? std::to_string(r.points) : "-";
    char error[32] = "-";
    if (r.rms_rel_error >= 0) std::snprintf(error, sizeof error, "%.4g", r.rms_rel_error);
    std::printf("%-6d %-24s %-9s %10.4g %10.4g %10.1f %12s\n", r.job, r.model.c_str(), points.c_str(), r.max_force,
                r.max_jump, r.p99_us, error);
  }
}

}  // namespace

void RegisterContactStudy() {
  Study s;
  s.name = kContactStudy;
  s.description = "models compared along a trajectory";
  s.sections = {
      {"models", "list of model names (default: the scene's)", "the contact models every job compares"},
      {"moving_body", "a body's name (default: the field body)", "the body the trajectory moves; the other stays at its pose"},
      {"trajectory", "mapping (below; required)", "the moving body's motion, cycle by cycle"},
      {"reference", "a model name, or a mapping: model, points, levels, resolution",
       "what the errors in summary.csv are measured against: a model on the same scene, or on a denser version of it "
       "(points, levels: its pointshell; resolution: its field)"},
      {"reference_every", "integer >= 1 (default 1)", "evaluate the reference every N cycles (a costly reference)"},
  };
  s.required = {"trajectory"};
  s.tables = {CyclesTable(), SummaryTable()};
  s.derived = {{ConvergenceTable(), [](const std::vector<std::string>& tables) { return ConvergenceCsv(tables[1]); }}};
  s.replayable = true;
  s.run = RunContactStudy;
  s.reference = TrajectoryReference;
  RegisterStudy(std::move(s));
}

}  // namespace contactlab
