// `contactlab run CONFIG.yaml [--out DIR] [--set key=value ...] [--list-jobs] [--job I]
// [--slurm [--dry-run] [--partition P] [--time T] [--cpus-per-task C] [--mem M]]` and
// `contactlab merge DIR... --out DIR [--partial]` / `contactlab merge --sweep DIR --jobs N --out DIR`: the
// experiment harness's entry points. A sweep can be spread over a cluster: --list-jobs prints
// the sweep points, --job I runs one of them, --slurm writes and submits a Slurm array of them
// plus a merge job (experiment/slurm_script.h), and merge joins the pieces.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_registry.h"
#include "experiment/experiment_config.h"
#include "experiment/result_table.h"
#include "experiment/runner.h"
#include "scene/scene.h"
#include "experiment/slurm_script.h"
#include "experiment/study.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/input_files.h"
#include "util/output_target.h"

namespace contactlab::cli {
namespace {

struct RunArgs {
  std::string config;
  std::string out;
  std::vector<std::string> overrides;
  std::string profile;
  bool list_jobs = false;
  std::vector<int> jobs;
  int parallel = 0;
  std::string cache;
  bool no_cache = false;
  bool slurm = false;
  bool dry_run = false;
  SlurmOptions slurm_options;
};

// --slurm: the array and merge scripts for every sweep point, submitted unless --dry-run.
void SubmitToSlurm(const RunArgs& args, const ExperimentConfig& config, int jobs) {
  if (!args.jobs.empty()) Fail("--slurm", "runs the whole sweep; it cannot be combined with --job");
  namespace fs = std::filesystem;
  std::error_code ec;
  SweepCommand command;
  command.contactlab = fs::read_symlink("/proc/self/exe", ec);
  if (ec) Fail("/proc/self/exe", "cannot find the running program: " + ec.message());
  command.config = fs::absolute(config.file);
  for (const std::string& o : args.overrides) command.run_args.insert(command.run_args.end(), {"--set", o});
  if (!args.profile.empty()) command.run_args.insert(command.run_args.end(), {"--profile", args.profile});
  if (!args.cache.empty()) command.run_args.insert(command.run_args.end(), {"--cache", fs::absolute(args.cache).string()});
  if (args.no_cache) command.run_args.push_back("--no-cache");
  command.out_dir = fs::absolute(args.out.empty() ? fs::path("results") / config.name : fs::path(args.out)).lexically_normal();
  CheckOutputFolderWritable(command.out_dir, "--out");
  command.name = config.name;
  command.jobs = jobs;
  const fs::path dir = WriteSlurmScripts(command, args.slurm_options);
  if (args.dry_run) {
    std::printf("wrote %s/array.sbatch (%d tasks), %s/merge.sbatch and %s/submit.sh; not submitted\n",
                dir.c_str(), jobs, dir.c_str(), dir.c_str());
    std::printf("submit with: %s/submit.sh\n", dir.c_str());
    return;
  }
  const SlurmSubmission sub = SubmitSlurmScripts(dir);
  std::printf("submitted array job %s (%d tasks) and merge job %s (after the array); results: %s\n",
              sub.array_job.c_str(), jobs, sub.merge_job.c_str(), command.out_dir.c_str());
  std::printf("array_job=%s\nmerge_job=%s\n", sub.array_job.c_str(), sub.merge_job.c_str());
}

// Runs WORK; when it throws, removes the folders on the way to OUT_DIR that did not exist
// before and are still empty, so that a failed run leaves no empty results folder behind.
template <typename Work>
auto RunRemovingNewEmptyFolders(const std::filesystem::path& out_dir, Work&& work) -> decltype(work()) {
  namespace fs = std::filesystem;
  std::vector<fs::path> created;  // innermost first
  std::error_code ec;
  for (fs::path p = fs::absolute(out_dir, ec).lexically_normal(); !p.empty() && !fs::exists(p, ec);
       p = p.parent_path()) {
    created.push_back(p);
    if (p == p.parent_path()) break;
  }
  try {
    return work();
  } catch (...) {
    for (const fs::path& p : created) {
      if (!fs::exists(p, ec)) continue;  // the results folder itself is made only at the commit
      if (!fs::is_directory(p, ec) || !fs::is_empty(p, ec) || !fs::remove(p, ec)) break;
    }
    throw;
  }
}

void RunRun(const RunArgs& args) {
  const ExperimentConfig config = LoadExperimentConfig(RequireDataFile(args.config), args.overrides, args.profile);
  // Loading checked every job; listing them needs only their labels.
  if (args.list_jobs) {
    for (std::size_t j = 0, n = JobCount(config); j < n; ++j) std::printf("%zu\t%s\n", j, JobLabel(config, j).c_str());
    return;
  }
  if (args.slurm) {
    SubmitToSlurm(args, config, static_cast<int>(JobCount(config)));
    return;
  }
  if (args.dry_run) Fail("--dry-run", "only applies with --slurm");
  RunOptions options;
  options.out_dir = args.out.empty() ? std::filesystem::path("results") / config.name : std::filesystem::path(args.out);
  if (args.jobs.size() == 1 && args.out.empty()) options.out_dir /= "job-" + std::to_string(args.jobs.front());
  // The results folder and its files are checked before any job runs: writable, and none of
  // them a file the config named (the config itself, its scene, its trajectory).
  const Study& study = StudyOf(config);
  CheckOutputFolderWritable(options.out_dir, "--out");
  for (const std::string& file : study.Files()) {
    CheckOutputTarget(options.out_dir / file, "--out");
    CheckOutputIsNoRecordedInput(options.out_dir / file, "--out");
  }
  options.assets.cache_dir = args.cache;
  options.assets.use_cache = !args.no_cache;
  options.assets.verbose = false;
  options.parallel_jobs = args.parallel;
  RunRemovingNewEmptyFolders(options.out_dir, [&] { study.run(config, options, args.jobs); });
  std::string list;
  for (const std::string& f : study.Files()) list += (list.empty() ? "" : ", ") + f;
  std::printf("results: %s (%s)\n", options.out_dir.string().c_str(), list.c_str());
}

const CommandRegistration kRunCommands([](CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run = app.add_subcommand("run", "Run an experiment config: every sweep point and model along the "
                                            "trajectory; writes CSV and meta.json");
  run->add_option("CONFIG", args->config, "experiment YAML (experiments/*.yaml)")->required();
  run->add_option("--out", args->out, "results folder (default results/NAME, or results/NAME/job-I with one --job)");
  run->add_option("--set", args->overrides, "override a config value: key.path=value (YAML value); repeatable");
  run->add_option("--profile", args->profile, "apply a named set of overrides from the config's 'profiles' (e.g. paper)");
  run->add_flag("--list-jobs", args->list_jobs, "print the sweep points (index and axis values) and exit");
  run->add_option("--job", args->jobs, "run only these sweep points (repeatable)");
  run->add_option("--parallel", args->parallel, "jobs run at once (default: all cores; 1 for timing experiments)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--cache", args->cache, "cache folder for fields and pointshells");
  run->add_flag("--no-cache", args->no_cache, "neither read nor write cached fields and pointshells");
  run->add_flag("--slurm", args->slurm,
                "write a Slurm array script (task I runs --job I into OUT/job-I) and a merge job after it "
                "into OUT/slurm/, submit both and print their ids");
  run->add_flag("--dry-run", args->dry_run, "with --slurm: write the scripts, do not submit");
  run->add_option("--partition", args->slurm_options.partition, "with --slurm: Slurm partition (default: the cluster's)");
  run->add_option("--time", args->slurm_options.time, "with --slurm: time limit per task (default 01:00:00)");
  run->add_option("--cpus-per-task", args->slurm_options.cpus_per_task, "with --slurm: CPUs per task (default 1)");
  run->add_option("--mem", args->slurm_options.mem, "with --slurm: memory per task, e.g. 4G (default: the cluster's)");
  run->callback([args] { RunRun(*args); });

  struct MergeArgs {
    std::vector<std::string> dirs;
    std::string out;
    std::string sweep;
    int jobs = 0;
    bool partial = false;
  };
  auto margs = std::make_shared<MergeArgs>();
  CLI::App* merge = app.add_subcommand("merge", "Join the results of single-job runs into one results folder");
  merge->add_option("DIRS", margs->dirs, "job result folders, joined in this order");
  merge->add_option("--sweep", margs->sweep,
                    "instead of DIRS: SWEEP/job-0 .. SWEEP/job-(N-1) of a --slurm run, each checked for complete "
                    "results (every failed task is named)");
  merge->add_option("--jobs", margs->jobs, "with --sweep: the number of sweep points N")->check(CLI::PositiveNumber);
  merge->add_option("--out", margs->out, "merged results folder")->required();
  merge->add_flag("--partial", margs->partial,
                  "merge some of the sweep's jobs (without it every job of the sweep must be in the folders)");
  merge->callback([margs] {
    std::vector<std::filesystem::path> paths(margs->dirs.begin(), margs->dirs.end());
    if (!margs->sweep.empty()) {
      if (!paths.empty()) Fail("merge", "give either result folders or --sweep, not both");
      if (margs->jobs < 1) Fail("--sweep", "needs --jobs N (the number of sweep points)");
      paths = SweepTaskFolders(margs->sweep, margs->jobs);
    } else if (paths.empty()) {
      Fail("merge", "no result folders given (DIRS or --sweep DIR --jobs N)");
    }
    CheckOutputFolderWritable(margs->out, "--out");
    for (const auto& p : paths) CheckOutputIsNotInput(margs->out, p, "--out");
    MergeResults(paths, margs->out, MergeOptions{.partial = margs->partial});
    std::printf("merged %zu folders into %s\n", paths.size(), margs->out.c_str());
  });
});

// `contactlab params [--out FILE]`: every scene parameter, block by block, from the tables that
// parse them (scene/scene.h), as Markdown; docs/scene-reference.md is its output.
// The sections of the studies that declare their keys in tables, one heading per study.
// The experiment config's keys: those every study reads, then each study's sections and the
// reference of their keys.
std::string StudyReference() {
  std::string s = "## Experiment configs\n\nThe top-level keys of an experiment config (`experiments/*.yaml`; "
                  "an annotated example is in docs/experiments.md). Every study reads these:\n\n" +
                  ConfigKeyTable(CommonConfigKeys());
  for (const Study& study : Studies()) {
    s += "## Study `" + study.name + "`\n\n" + study.description + ". Its own top-level keys:\n\n" +
         ConfigKeyTable(study.sections);
    if (study.reference) s += study.reference();
  }
  return s;
}

const CommandRegistration kParams([](CLI::App& app) {
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "params", "Print the reference of every scene parameter (key, type, range, default, unit, cache, sweep axis) "
                "as Markdown, from the tables that parse them");
  cmd->add_option("--out", *out, "write to FILE instead of standard output");
  cmd->callback([out] {
    const std::string text = "# Scene parameters\n\nGenerated by `contactlab params` from the parameter tables "
                             "(`src/scene/scene.cc`, `src/contact/contact_params.cc` and each "
                             "model's own, from its registry entry); a sweep axis "
                             "may name a key in its column alone (`sweep: {points: [...]}`), any other key by its "
                             "path (`scene.bodies[role=field].field.mode`). \"cached in\" lists the cached artefacts "
                             "whose cache key holds the value. The studies' own sections follow the scene's.\n\n" +
                             SceneReference() + StudyReference();
    if (out->empty()) {
      std::cout << text;
    } else {
      CheckOutputWritable(*out, "--out");
      WriteFileAtomically(*out, text);
    }
  });
});

// `contactlab columns [--json]`: every study's result tables and their declared columns (name,
// unit, meaning; experiment/result_table.h), as Markdown or as JSON {study: {file: [column...]}}.
// The figure scripts' test checks the columns they read against this list.
const CommandRegistration kColumns([](CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "columns", "Print the columns of every study's result tables (name, unit, meaning), as declared by their writers");
  cmd->add_flag("--json", *json, "as JSON: {study: {file: [{name, unit, meaning}, ...]}}");
  cmd->callback([json] {
    if (*json) {
      nlohmann::json all = nlohmann::json::object();
      for (const Study& study : Studies()) all[study.name] = study.ColumnsJson();
      std::cout << all.dump(2) << "\n";
      return;
    }
    for (const Study& study : Studies()) {
      std::cout << "## Study `" << study.name << "`\n";
      for (const ResultTable* table : study.AllTables()) {
        std::cout << "\n### " << table->file << ": " << table->meaning << "\n\n| column | unit | meaning |\n|---|---|---|\n";
        for (const auto& c : ColumnsJson(*table)) {
          std::cout << "| " << c["name"].get<std::string>() << " | " << c["unit"].get<std::string>() << " | "
                    << c["meaning"].get<std::string>() << " |\n";
          if (table->keys != TableKeys::kNone && c["name"] == "job") {
            std::cout << "| (sweep axes) | | one column per axis of the config's sweep"
                      << (table->keys == TableKeys::kJobAndOtherAxes
                              ? ", except those named like a column below"
                              : "; one named like a column below is written sweep.NAME")
                      << " |\n";
          }
        }
      }
      std::cout << "\n";
    }
  });
});

}  // namespace
}  // namespace contactlab::cli
