// Slurm array and merge scripts for an experiment sweep, their submission through sbatch, and
// the merge's check that every task left complete results.
#include "experiment/slurm_script.h"

#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "experiment/study.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/shell_quote.h"

namespace contactlab {
namespace fs = std::filesystem;

namespace {

// Standard output of COMMAND run by /bin/sh with stderr joined; sets *STATUS to its exit code.
std::string RunCommand(const std::string& command, int* status) {
  std::string out;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (p == nullptr) {
    *status = -1;
    return "cannot start /bin/sh";
  }
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int raw = ::pclose(p);
  *status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

// The job id in `sbatch --parsable` output ("ID" or "ID;CLUSTER"), or empty.
std::string ParsableJobId(const std::string& out) {
  const std::string last = out.substr(out.find_last_of('\n') == std::string::npos ? 0 : out.find_last_of('\n') + 1);
  const std::string id = last.substr(0, last.find(';'));
  static const std::regex digits("[0-9]+");
  return std::regex_match(id, digits) ? id : std::string();
}

// "#SBATCH" lines shared by both scripts.
std::string ResourceLines(const SlurmOptions& o, bool with_cpus_and_mem) {
  std::string s;
  if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
  s += "#SBATCH --time=" + o.time + "\n";
  if (with_cpus_and_mem) {
    s += "#SBATCH --cpus-per-task=" + std::to_string(o.cpus_per_task) + "\n";
    if (!o.mem.empty()) s += "#SBATCH --mem=" + o.mem + "\n";
  }
  return s;
}

// A Slurm job name: the experiment name reduced to safe characters.
std::string JobName(const std::string& name) {
  std::string s = "contactlab-";
  for (char c : name) s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
  return s;
}

}  // namespace

void CheckSlurmOptions(const SlurmOptions& o) {
  static const std::regex time("[0-9]+|[0-9]+:[0-9]{1,2}|[0-9]+:[0-9]{1,2}:[0-9]{1,2}|[0-9]+-[0-9]+"
                               "|[0-9]+-[0-9]+:[0-9]{1,2}|[0-9]+-[0-9]+:[0-9]{1,2}:[0-9]{1,2}");
  static const std::regex partition("[A-Za-z0-9_.,-]+");
  static const std::regex mem("[0-9]+[KMGT]?");
  if (!std::regex_match(o.time, time)) {
    Fail("--time", "'" + o.time + "' is not a Slurm time (MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS)");
  }
  if (!o.partition.empty() && !std::regex_match(o.partition, partition)) {
    Fail("--partition", "'" + o.partition + "' is not a partition name (letters, digits, '_', '.', '-', ',')");
  }
  if (o.cpus_per_task < 1) Fail("--cpus-per-task", "must be at least 1, got " + std::to_string(o.cpus_per_task));
  if (!o.mem.empty() && !std::regex_match(o.mem, mem)) {
    Fail("--mem", "'" + o.mem + "' is not a Slurm memory size (a number with an optional K, M, G or T)");
  }
}

SlurmScripts MakeSlurmScripts(const SweepCommand& c, const SlurmOptions& o) {
  CheckSlurmOptions(o);
  if (c.jobs < 1) Fail(c.config.string(), "the sweep has no jobs to submit");
  const std::string out = c.out_dir.string();
  if (out.find_first_of(" \t\n%") != std::string::npos) {
    Fail(out, "a Slurm results folder may not contain spaces or '%' (#SBATCH --output cannot quote them)");
  }
  const std::string slurm = (c.out_dir / "slurm").string();
  SlurmScripts s;

  // The array: task I runs sweep point I into OUT/job-I.
  std::ostringstream a;
  a << "#!/bin/bash\n"
    << "# Experiment '" << c.name << "': sweep points 0.." << c.jobs - 1 << ", one per array task.\n"
    << "# Written by `contactlab run --slurm`; submit with submit.sh (or sbatch this file, then\n"
    << "# merge.sbatch with --dependency=afterany:<this job's id>).\n"
    << "#SBATCH --job-name=" << JobName(c.name) << "\n"
    << "#SBATCH --array=0-" << c.jobs - 1 << "\n"
    << ResourceLines(o, true)
    << "#SBATCH --output=" << slurm << "/job-%a.log\n"
    << "set -euo pipefail\n"
    << "exec " << ShellQuote(c.contactlab.string()) << " run " << ShellQuote(c.config.string());
  for (const std::string& arg : c.run_args) a << " " << ShellQuote(arg);
  a << " --job \"$SLURM_ARRAY_TASK_ID\" --out " << ShellQuote(out) << "/job-\"$SLURM_ARRAY_TASK_ID\"\n";
  s.array = a.str();

  // The merge: after every task has ended, whatever its outcome; fails naming failed tasks.
  std::ostringstream m;
  m << "#!/bin/bash\n"
    << "# Experiment '" << c.name << "': joins job-0..job-" << c.jobs - 1 << " into " << out << " (summary.csv as a\n"
    << "# local run writes it). Submitted with --dependency=afterany:<array id>; it fails, naming each\n"
    << "# task that left no complete results, rather than merge a partial sweep.\n"
    << "#SBATCH --job-name=" << JobName(c.name) << "-merge\n"
    << ResourceLines(o, false)
    << "#SBATCH --cpus-per-task=1\n"
    << "#SBATCH --output=" << slurm << "/merge.log\n"
    << "set -euo pipefail\n"
    << "exec " << ShellQuote(c.contactlab.string()) << " merge --sweep " << ShellQuote(out) << " --jobs " << c.jobs
    << " --out " << ShellQuote(out) << "\n";
  s.merge = m.str();

  // submit.sh: the two submissions, the second depending on the first.
  std::ostringstream u;
  u << "#!/bin/bash\n"
    << "# Submits the sweep of experiment '" << c.name << "': the array, then the merge after it.\n"
    << "set -euo pipefail\n"
    << "dir=" << ShellQuote(slurm) << "\n"
    << "array=$(sbatch --parsable \"$dir/array.sbatch\")\n"
    << "array=${array%%;*}\n"
    << "merge=$(sbatch --parsable --dependency=afterany:\"$array\" \"$dir/merge.sbatch\")\n"
    << "merge=${merge%%;*}\n"
    << "echo \"array job $array (" << c.jobs << " tasks), merge job $merge; results in \"" << ShellQuote(out) << "\n";
  s.submit = u.str();
  return s;
}

fs::path WriteSlurmScripts(const SweepCommand& command, const SlurmOptions& options) {
  const SlurmScripts s = MakeSlurmScripts(command, options);
  const fs::path dir = command.out_dir / "slurm";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) Fail(dir.string(), "cannot create the folder: " + ec.message());
  for (const auto& [name, text] : {std::pair<const char*, const std::string&>{"array.sbatch", s.array},
                                   {"merge.sbatch", s.merge},
                                   {"submit.sh", s.submit}}) {
    WriteFileAtomically(dir / name, text);
    fs::permissions(dir / name, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add, ec);
  }
  return dir;
}

SlurmSubmission SubmitSlurmScripts(const fs::path& slurm_dir) {
  SlurmSubmission sub;
  int status = 0;
  const std::string array_out = RunCommand("sbatch --parsable " + ShellQuote((slurm_dir / "array.sbatch").string()), &status);
  sub.array_job = ParsableJobId(array_out);
  if (status != 0 || sub.array_job.empty()) {
    Fail((slurm_dir / "array.sbatch").string(), "sbatch failed (exit " + std::to_string(status) + "): " + array_out);
  }
  const std::string merge_out = RunCommand("sbatch --parsable --dependency=afterany:" + sub.array_job + " " +
                                               ShellQuote((slurm_dir / "merge.sbatch").string()),
                                           &status);
  sub.merge_job = ParsableJobId(merge_out);
  if (status != 0 || sub.merge_job.empty()) {
    int ignored = 0;
    RunCommand("scancel " + sub.array_job, &ignored);
    Fail((slurm_dir / "merge.sbatch").string(), "sbatch failed (exit " + std::to_string(status) + "): " + merge_out +
                                                    "; the array job " + sub.array_job + " was cancelled");
  }
  return sub;
}

std::vector<fs::path> SweepTaskFolders(const fs::path& out_dir, int jobs) {
  if (jobs < 1) Fail(out_dir.string(), "--jobs must be at least 1");
  std::vector<fs::path> dirs;
  std::string problems;
  int failed = 0;
  for (int i = 0; i < jobs; ++i) {
    const fs::path dir = out_dir / ("job-" + std::to_string(i));
    dirs.push_back(dir);
    std::string why;
    std::error_code ec;
    // meta.json last (a task writes it after its tables): the study it names says which tables
    // the task must have left.
    if (!fs::is_regular_file(dir / "meta.json", ec)) why = "no meta.json";
    if (why.empty()) {
      try {
        const nlohmann::json meta = nlohmann::json::parse(ReadWholeFile(dir / "meta.json"));
        if (meta.value("jobs", nlohmann::json::array()) != nlohmann::json::array({i})) {
          why = "meta.json holds jobs " + meta.value("jobs", nlohmann::json::array()).dump() + ", not [" +
                std::to_string(i) + "]";
        }
      } catch (const nlohmann::json::exception& e) {
        why = std::string("meta.json is not valid JSON: ") + e.what();
      }
    }
    if (why.empty()) {
      try {
        for (const std::string& name : StudyOfResults(dir).TableFiles()) {
          if (why.empty() && !fs::is_regular_file(dir / name, ec)) why = "no " + name;
        }
      } catch (const Error& e) {
        why = e.what();
      }
    }
    if (!why.empty()) {
      ++failed;
      problems += "\n  task " + std::to_string(i) + ": " + dir.string() + ": " + why + " (the task failed or did not " +
                  "finish; log: " + (out_dir / "slurm" / ("job-" + std::to_string(i) + ".log")).string() + ")";
    }
  }
  if (failed > 0) {
    Fail(out_dir.string(), std::to_string(failed) + " of " + std::to_string(jobs) +
                               " sweep tasks left no complete results; nothing merged:" + problems);
  }
  return dirs;
}

}  // namespace contactlab
