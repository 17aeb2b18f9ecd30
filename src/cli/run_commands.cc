// `contactlab run CONFIG.yaml [--out DIR] [--set key=value ...] [--list-jobs] [--job I]`
// and `contactlab merge DIR... --out DIR`: the experiment harness's entry points. A sweep
// can be spread over a cluster: --list-jobs prints the sweep points, --job I runs one of them
// (e.g. as a Slurm array task), and merge joins the pieces.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_registry.h"
#include "experiment/experiment_config.h"
#include "experiment/runner.h"
#include "util/data_path.h"
#include "util/error.h"

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
};

void RunRun(const RunArgs& args) {
  const ExperimentConfig config = LoadExperimentConfig(RequireDataFile(args.config), args.overrides, args.profile);
  const std::vector<Job> jobs = ExpandJobs(config);
  if (args.list_jobs) {
    for (const Job& j : jobs) std::printf("%d\t%s\n", j.index, j.Label().c_str());
    return;
  }
  RunOptions options;
  options.out_dir = args.out.empty() ? std::filesystem::path("results") / config.name : std::filesystem::path(args.out);
  if (args.jobs.size() == 1 && args.out.empty()) options.out_dir /= "job-" + std::to_string(args.jobs.front());
  options.assets.cache_dir = args.cache;
  options.assets.use_cache = !args.no_cache;
  options.assets.verbose = false;
  options.parallel_jobs = args.parallel;
  std::fprintf(stderr, "experiment %s: %zu of %zu jobs, models:", config.name.c_str(),
               args.jobs.empty() ? jobs.size() : args.jobs.size(), jobs.size());
  for (const auto& m : config.models) std::fprintf(stderr, " %s", m.c_str());
  std::fprintf(stderr, "\n");
  const std::vector<SummaryRow> rows = RunExperiment(config, options, args.jobs);
  std::printf("%-6s %-24s %-9s %10s %10s %10s %12s\n", "job", "model", "points", "max|F| N", "jump N", "p99 us",
              "rel.err");
  for (const SummaryRow& r : rows) {
    std::printf("%-6d %-24s %-9d %10.4g %10.4g %10.1f %12.4g\n", r.job, r.model.c_str(), r.points, r.max_force,
                r.max_jump, r.p99_us, r.rms_rel_error);
  }
  std::printf("results: %s (cycles.csv, summary.csv, convergence.csv, meta.json)\n", options.out_dir.string().c_str());
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
  run->callback([args] { RunRun(*args); });

  auto dirs = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>();
  CLI::App* merge = app.add_subcommand("merge", "Join the results of single-job runs into one results folder");
  merge->add_option("DIRS", *dirs, "job result folders")->required();
  merge->add_option("--out", *out, "merged results folder")->required();
  merge->callback([dirs, out] {
    std::vector<std::filesystem::path> paths(dirs->begin(), dirs->end());
    MergeResults(paths, *out);
    std::printf("merged %zu folders into %s\n", paths.size(), out->c_str());
  });
});

}  // namespace
}  // namespace contactlab::cli
