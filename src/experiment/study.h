// What an experiment config runs, named by its `study:` key, registered like a contact model:
// a study declares the config sections it reads, the sweep aliases it adds, its result files and
// how to check, run and merge its jobs. The harness (run, merge, Slurm, the viewer) asks the
// study, never tests its name or sniffs a results folder's files; meta.json records it.
//
// Adding a study: a folder src/experiment/studies/my_study/ with a source file defining
// `void RegisterMyStudy()` that calls RegisterStudy, its CMakeLists.txt holding one
// `contactlab_study(SOURCES my_study.cc REGISTER RegisterMyStudy)` line, and its
// add_subdirectory in src/experiment/CMakeLists.txt. The studies today, under studies/: contact
// (contact/contact_study.h: models along a trajectory), deformed-field
// (deformed_field/deformed_field_study.h), closed-loop (closed_loop/closed_loop_study.h) and
// many-bodies (many_bodies/many_bodies_study.h: a tool through a scene of many bodies).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/experiment_config.h"
#include "experiment/result_table.h"
#include "util/config_node.h"

namespace contactlab {

struct RunOptions;

// A top-level key of an experiment config: its name, the form of its value and what it does,
// as `contactlab params` prints it.
struct ConfigKey {
  std::string key;
  std::string value;    // "text", "list of model names", "mapping (below)", ...
  std::string meaning;  // one line
};

// The top-level keys every study reads (name, description, study, scene, metrics, sweep,
// profiles), declared once: the config's key check and the reference both read them.
const std::vector<ConfigKey>& CommonConfigKeys();

// KEYS as a Markdown table (key, value, meaning).
std::string ConfigKeyTable(const std::vector<ConfigKey>& keys);

struct Study {
  std::string name;         // what `study:` says
  std::string description;  // one line for listings and errors
  // Top-level config keys it reads beyond CommonConfigKeys(). A key no study reads is unknown;
  // a key only other studies read is refused, naming them.
  std::vector<ConfigKey> sections;
  bool Reads(const std::string& key) const;
  std::vector<std::string> required;  // of `sections`, those a config must give
  // The sweep aliases it adds (alias, key path), e.g. (k_vc, loop.k_vc).
  std::vector<std::pair<std::string, std::string>> aliases;
  // Its result tables, each with its columns declared (experiment/result_table.h): every job's
  // rows under one header, joined in job order by a merge.
  std::vector<ResultTable> tables;
  // Tables computed from the tables (their whole text, in `tables` order), written by the run
  // and recomputed by a merge, e.g. contact's convergence.csv from summary.csv.
  struct Derived {
    ResultTable table;
    std::function<std::string(const std::vector<std::string>& tables)> compute;
  };
  std::vector<Derived> derived;
  bool timing = false;      // its numbers are times: jobs run one at a time (metrics.timing may say otherwise)
  bool many_bodies = false; // its scenes are scenes of many bodies (a tool and pairs); the others' take two
  bool replayable = false;  // its cycles.csv holds trajectories the viewer replays
  // Checks what the study reads of CONFIG (its sections) for JOB, after the scene, the models
  // and the sweep parsed; called for every job of the sweep, one at a time. ROOT is the config
  // document. Throws Error naming file and key.
  std::function<void(const ExperimentConfig& config, const ConfigNode& root, const Job& job)> check;
  // Runs the jobs JOBS of CONFIG (all of them when empty), writes Files() into OPTIONS.out_dir
  // (each atomically, after every job finished) and prints a table of the results.
  std::function<void(const ExperimentConfig& config, const RunOptions& options, const std::vector<int>& jobs)> run;
  // The reference of its sections' keys (Markdown, from their parameter tables) for `contactlab
  // params`; null when it has none.
  std::function<std::string()> reference;

  // What a finished run's folder holds: the tables, the derived files and meta.json.
  std::vector<std::string> Files() const;
  // The files of `tables`, in order.
  std::vector<std::string> TableFiles() const;
  // Every table it writes, `tables` then the derived ones.
  std::vector<const ResultTable*> AllTables() const;
  // Its tables' columns as meta.json records them: {"<file>": ColumnsJson(table), ...}.
  nlohmann::json ColumnsJson() const;
};

// Adds STUDY; a second study of the same name is a programming error (std::logic_error).
void RegisterStudy(Study study);
// Every registered study, registering them on first use.
const std::vector<Study>& Studies();
const Study* FindStudy(std::string_view name);
std::vector<std::string> StudyNames();
// CONFIG's study (ParseExperimentConfig has checked it is registered).
const Study& StudyOf(const ExperimentConfig& config);
// The study that wrote the results folder DIR, from its meta.json ("study", or the `study:` of
// its resolved_config for runs recorded before meta.json named it). Throws Error naming the file
// when meta.json is missing or unreadable or names no registered study.
const Study& StudyOfResults(const std::filesystem::path& dir);

// Writes a run's results into OUT_DIR: STUDY's tables (TABLES, their text in the order of
// study.tables), the derived files computed from them, and META as meta.json with the row count
// and the declared columns of each table, as one commit (util/atomic_folder.h): a reader sees
// the old folder or the new one, and a failure leaves the old one as it was. Of an old folder's
// entries the result files of any study and meta.json are replaced; every other entry (Slurm
// scripts, job folders, figures, notes) is kept. Runs and merges both write through it.
void WriteStudyResults(const Study& study, const std::filesystem::path& out_dir, const std::vector<std::string>& tables,
                       const nlohmann::json& meta);

}  // namespace contactlab
