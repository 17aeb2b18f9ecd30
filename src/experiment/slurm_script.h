// Running an experiment's sweep on a Slurm cluster: an `sbatch --array` script whose task I
// runs sweep point I (`contactlab run CONFIG --job I --out OUT/job-I`), and a merge script
// that runs once every task has ended and joins OUT/job-0 .. OUT/job-(N-1) into OUT, failing
// and naming each task that left no complete results. Scripts go to OUT/slurm/.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace contactlab {

// Resources asked for each array task (and, with time, for the merge job).
struct SlurmOptions {
  std::string partition;          // empty: the cluster's default partition
  std::string time = "01:00:00";  // per task: MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS
  int cpus_per_task = 1;
  std::string mem;                // per task, e.g. "4G" (empty: the cluster's default)
};

// What the array tasks run.
struct SweepCommand {
  std::filesystem::path contactlab;   // the program, absolute
  std::filesystem::path config;       // the experiment config, absolute
  std::vector<std::string> run_args;  // further `contactlab run` arguments (--set k=v, --profile P, ...)
  std::filesystem::path out_dir;      // results folder, absolute; tasks write OUT/job-I
  std::string name;                   // experiment name (Slurm job names)
  int jobs = 0;                       // sweep points: the array is 0..jobs-1
};

struct SlurmScripts {
  std::string array;   // OUT/slurm/array.sbatch
  std::string merge;   // OUT/slurm/merge.sbatch (its dependency is given when it is submitted)
  std::string submit;  // OUT/slurm/submit.sh: submits both, as `contactlab run --slurm` does
};

// Checks OPTIONS; throws Error naming the option and what is wrong.
void CheckSlurmOptions(const SlurmOptions& options);

// The three scripts' text. Throws Error for bad options or a sweep with no jobs.
SlurmScripts MakeSlurmScripts(const SweepCommand& command, const SlurmOptions& options);

// Writes the scripts into OUT/slurm (each atomically, executable); returns that folder.
std::filesystem::path WriteSlurmScripts(const SweepCommand& command, const SlurmOptions& options);

struct SlurmSubmission {
  std::string array_job;  // Slurm job id of the array
  std::string merge_job;  // Slurm job id of the merge
};

// Submits SLURM_DIR/array.sbatch, then SLURM_DIR/merge.sbatch with --dependency=afterany on
// the array (through `sbatch --parsable`, from $PATH). Throws Error with sbatch's own message
// when a submission fails; if the merge cannot be submitted, the array is cancelled (scancel).
SlurmSubmission SubmitSlurmScripts(const std::filesystem::path& slurm_dir);

// The folders OUT/job-0 .. OUT/job-(JOBS-1) in order, after checking that each holds the
// complete results of its task (cycles.csv, summary.csv, meta.json naming that job). Throws
// Error naming every task that did not, with its log OUT/slurm/job-I.log.
std::vector<std::filesystem::path> SweepTaskFolders(const std::filesystem::path& out_dir, int jobs);

}  // namespace contactlab
