// Runs an experiment's jobs (in parallel unless the config measures timing), one call of the
// study's job function per sweep point (experiment/runner.h). Merging of single-job runs is in
// merge_results.cc.
#include "experiment/runner.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

#include "util/error.h"
#include "util/progress.h"

namespace contactlab {
namespace fs = std::filesystem;

JobsRun RunJobs(const ExperimentConfig& config, const std::vector<int>& job_indices, const RunOptions& options,
                const std::function<void(std::size_t, const Job&)>& run) {
  JobsRun out;
  out.indices = job_indices;
  const int total = int(JobCount(config));
  if (out.indices.empty()) {
    for (int j = 0; j < total; ++j) out.indices.push_back(j);
  }
  for (int i : out.indices) {
    if (i < 0 || i >= total) {
      Fail(config.file, "job " + std::to_string(i) + " does not exist (the sweep has " + std::to_string(total) +
                            " jobs: 0.." + std::to_string(total - 1) + ")");
    }
  }
  // Each job is built when a worker takes it and dropped when it ends, so a sweep's jobs (each
  // holding its own copy of the config's documents) are not all in memory at once. They are
  // built one at a time: each is cloned from the config's documents.
  std::mutex building;
  int parallel = options.parallel_jobs;
  if (parallel <= 0) parallel = config.timing ? 1 : int(std::max(1u, std::thread::hardware_concurrency()));
  out.parallel = std::max(1, std::min<int>(parallel, int(out.indices.size())));

  const auto t0 = std::chrono::steady_clock::now();
  Progress progress("experiment " + config.name, std::int64_t(out.indices.size()));
  if (!options.progress) progress.Finish();
  // A failing job does not cancel the others (whose builds are isolated from cancellation
  // anyway): each job's exception is kept, every job finishes, and the first error in job
  // order is rethrown, so the reported error does not depend on thread timing.
  std::vector<std::exception_ptr> errors(out.indices.size());
  tbb::task_arena arena(out.parallel);
  arena.execute([&] {
    tbb::parallel_for(std::size_t(0), out.indices.size(), [&](std::size_t i) {
      try {
        const Job job = [&] {
          const std::lock_guard<std::mutex> lock(building);
          return ExpandJob(config, std::size_t(out.indices[i]));
        }();
        run(i, job);
      } catch (...) {
        errors[i] = std::current_exception();
      }
      if (options.progress) progress.Advance();
    });
  });
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace contactlab
