// Runs an experiment's jobs for its study (experiment/study.h), in parallel unless the config
// measures timing, and merges the results of single-job runs. A study formats its tables in
// memory and writes them with WriteStudyResults (temporary names renamed), so a failed or
// interrupted run never leaves a file that looks complete.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "experiment/experiment_config.h"
#include "scene/scene_assets.h"

namespace contactlab {

struct RunOptions {
  std::filesystem::path out_dir;  // results folder (created)
  AssetOptions assets;
  int parallel_jobs = 0;          // 0: all cores, or 1 when the config measures timing
  bool progress = true;
};

// How a set of jobs ran: the sweep indices run, the jobs run at once and the wall time.
struct JobsRun {
  std::vector<int> indices;
  int parallel = 1;
  double wall_seconds = 0;
};

// Runs RUN(slot, job) for the jobs JOB_INDICES of CONFIG's sweep (every job when empty; SLOT
// counts the jobs run from 0), OPTIONS.parallel_jobs at once (0: all cores, or 1 when the config
// measures timing), showing progress. Each job is built when it starts and dropped when it
// ends (never the whole sweep at once). Throws Error naming the config
// for an index outside the sweep. A failing job cancels no other; the first error in job order
// is rethrown.
JobsRun RunJobs(const ExperimentConfig& config, const std::vector<int>& job_indices, const RunOptions& options,
                const std::function<void(std::size_t, const Job&)>& run);

// How a merge treats an incomplete sweep.
struct MergeOptions {
  bool partial = false;  // merge some of a sweep's jobs (without it, every job must be present)
};

// Joins the results of single-job runs (folders holding the study's tables and meta.json) into
// OUT_DIR, recomputing the derived files (convergence.csv). Checks every folder first and
// writes nothing when one fails: a missing or cut-short table (a row of another shape than its
// header, fewer rows than its meta.json counted), another study, experiment, config or commit
// than the first folder's, a job already merged, or (unless OPTIONS.partial) a job of the sweep
// in no folder. Throws Error naming the folder or file and the problem.
void MergeResults(const std::vector<std::filesystem::path>& job_dirs, const std::filesystem::path& out_dir,
                  const MergeOptions& options = {});

}  // namespace contactlab
