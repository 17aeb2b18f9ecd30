// Runs an experiment's jobs (in parallel unless the config measures timing) and writes its
// results folder: cycles.csv and summary.csv (result_csv.h), convergence.csv
// (convergence_table.h) and meta.json (run_metadata.h), each file atomically after every job
// has finished. One job's work is in run_job.cc, merging of single-job runs in
// merge_results.cc.
#include "experiment/runner.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>

#include "experiment/convergence_table.h"
#include "experiment/result_csv.h"
#include "experiment/run_metadata.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/progress.h"

namespace contactlab {
namespace fs = std::filesystem;

std::vector<SummaryRow> RunExperiment(const ExperimentConfig& config, const RunOptions& options,
                                      const std::vector<int>& job_indices) {
  if (config.study != "contact") {
    Fail(config.file, "is a " + config.study + " study, not a contact study (experiment/deformed_field_study.h runs it)");
  }
  const std::vector<Job> all = ExpandJobs(config);
  std::vector<int> indices = job_indices;
  if (indices.empty()) {
    for (const Job& j : all) indices.push_back(j.index);
  }
  for (int i : indices) {
    if (i < 0 || i >= int(all.size())) {
      Fail(config.file, "job " + std::to_string(i) + " does not exist (the sweep has " + std::to_string(all.size()) +
                            " jobs: 0.." + std::to_string(int(all.size()) - 1) + ")");
    }
  }
  int parallel = options.parallel_jobs;
  if (parallel <= 0) parallel = config.timing ? 1 : int(std::max(1u, std::thread::hardware_concurrency()));
  parallel = std::min<int>(parallel, int(indices.size()));

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<JobResult> results(indices.size());
  {
    Progress progress("experiment " + config.name, std::int64_t(indices.size()));
    if (!options.progress) progress.Finish();
    // A failing job does not cancel the others (whose builds are isolated from cancellation
    // anyway): each job's exception is kept, every job finishes, and the first error in job
    // order is rethrown, so the reported error does not depend on thread timing.
    std::vector<std::exception_ptr> errors(indices.size());
    tbb::task_arena arena(std::max(1, parallel));
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), indices.size(), [&](std::size_t i) {
        try {
          results[i] = RunJob(config, all[std::size_t(indices[i])], options);
        } catch (...) {
          errors[i] = std::current_exception();
        }
        if (options.progress) progress.Advance();
      });
    });
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Everything is formatted in memory and written at the end, each file atomically.
  std::string cycles = CyclesCsvHeader(config), summary = SummaryCsvHeader(config);
  std::vector<SummaryRow> rows;
  for (const JobResult& r : results) {
    AppendCyclesCsv(config, r, &cycles);
    AppendSummaryCsv(config, r, &summary);
    rows.insert(rows.end(), r.summary.begin(), r.summary.end());
  }
  fs::create_directories(options.out_dir);
  WriteFileAtomically(options.out_dir / "cycles.csv", cycles);
  WriteFileAtomically(options.out_dir / "summary.csv", summary);
  WriteFileAtomically(options.out_dir / "convergence.csv", ConvergenceCsv(summary));
  WriteFileAtomically(options.out_dir / "meta.json", RunMetadata(config, indices, wall, parallel).dump(2) + "\n");
  return rows;
}

}  // namespace contactlab
