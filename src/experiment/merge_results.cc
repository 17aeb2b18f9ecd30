// Joins the results of single-job runs (a cluster array's tasks) into one results folder: the
// rows of each of the study's tables concatenated under one header (experiment/study.h), its
// derived files recomputed (a contact study's convergence.csv), meta.json listing every job and
// folder. Every input is checked before anything is written: its tables complete (each row as
// many cells as the header, the rows its meta.json counted), the same experiment, config and
// commits as the first folder, no job twice, and every job of the sweep present unless the
// merge is partial. Each output goes to a temporary name and is renamed at the end.
#include <algorithm>
#include <cstdlib>
#include <cstdint>
#include <set>

#include <nlohmann/json.hpp>

#include "experiment/csv_line.h"
#include "experiment/runner.h"
#include "experiment/study.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

// The data rows of TABLE's TEXT (its header aside), after checking that the text ends with a
// line break and that every row has as many cells as the header (cells read as the tables are
// written, experiment/csv_line.h). Sets *BODY to the offset where the rows begin. Throws Error
// naming the file (and the line) otherwise.
// Checks FILE's TEXT: complete rows, each of the header's shape, and, when the table has a
// `job` column, each row's job one of JOBS (its folder's meta.json). Returns the rows; BODY is
// where they start.
long CheckTableRows(const fs::path& file, const std::string& text, const std::set<int>& jobs, std::size_t* body) {
  if (text.empty()) Fail(file.string(), "is empty (an unfinished job?)");
  if (text.back() != '\n') Fail(file.string(), "does not end with a line break: it was cut short (an unfinished job?)");
  CsvReader reader(text, file.string());
  std::vector<std::string> header, cells;
  reader.Next(&header);
  *body = reader.end();
  const auto job_column = std::find(header.begin(), header.end(), "job");
  const std::size_t job_at = std::size_t(job_column - header.begin());
  long rows = 0;
  while (reader.Next(&cells)) {
    if (cells.size() != header.size()) {
      FailAtLine(file.string(), reader.line(),
                 std::to_string(cells.size()) + " cells, the header has " + std::to_string(header.size()) +
                     " (an unfinished job?)");
    }
    if (job_column != header.end()) {
      const std::string& cell = cells[job_at];
      char* end = nullptr;
      const long job = std::strtol(cell.c_str(), &end, 10);
      if (cell.empty() || *end != '\0' || job < 0 || job > long(kMaxSweepJobs) || jobs.count(int(job)) == 0) {
        FailAtLine(file.string(), reader.line(),
                   "job '" + cell + "' is none of the jobs its meta.json lists: the table and meta.json disagree");
      }
    }
    ++rows;
  }
  return rows;
}

// A job index or count in META_FILE's meta.json: an integer in [0, kMaxSweepJobs] (a larger one
// would wrap in an int: 2^32 read as job 0).
int JobNumber(const nlohmann::json& value, const fs::path& meta_file, const std::string& what) {
  if (!value.is_number_integer() || (value.is_number_unsigned() ? value.get<std::uint64_t>() > kMaxSweepJobs
                                                                : value.get<std::int64_t>() < 0 ||
                                                                      value.get<std::int64_t>() > std::int64_t(kMaxSweepJobs))) {
    Fail(meta_file.string(), what + " holds " + value.dump() + ", not a job number in [0, " +
                                 std::to_string(kMaxSweepJobs) + "]");
  }
  return int(value.get<std::int64_t>());
}

// META's value of KEY as text (empty when absent), for comparing folders.
std::string Field(const nlohmann::json& meta, const char* key) {
  if (!meta.contains(key)) return "";
  return meta[key].is_string() ? meta[key].get<std::string>() : meta[key].dump();
}

}  // namespace

void MergeResults(const std::vector<fs::path>& job_dirs, const fs::path& out_dir, const MergeOptions& options) {
  if (job_dirs.empty()) Fail(out_dir.string(), "nothing to merge");
  // The study that wrote the first folder (its meta.json says); every folder must be of it.
  const Study& study = StudyOfResults(job_dirs.front());
  const std::vector<std::string> tables = study.TableFiles();
  std::vector<std::string> headers(tables.size()), bodies(tables.size());
  std::vector<long> rows(tables.size(), 0);
  nlohmann::json meta;
  std::vector<int> jobs;
  std::set<int> seen;
  double wall = 0;
  for (const fs::path& dir : job_dirs) {
    const fs::path meta_file = dir / "meta.json";
    if (!fs::exists(meta_file)) Fail(dir.string(), "is missing meta.json (an unfinished job?)");
    if (const Study& s = StudyOfResults(dir); &s != &study) {
      Fail(meta_file.string(), "holds a " + s.name + " study, the first folder a " + study.name + " study");
    }
    for (const std::string& name : tables) {
      if (!fs::exists(dir / name)) Fail(dir.string(), "is missing " + name + " (an unfinished job?)");
    }
    nlohmann::json m;
    try {
      m = nlohmann::json::parse(ReadWholeFile(meta_file));
    } catch (const nlohmann::json::exception& e) {
      Fail(meta_file.string(), std::string("not valid JSON: ") + e.what());
    }
    if (meta.is_null()) meta = m;
    // The same experiment, config (after --set and --profile) and commits as the first folder.
    if (m.value("experiment", "") != meta.value("experiment", "")) {
      Fail(meta_file.string(), "belongs to experiment '" + m.value("experiment", "") + "', the first folder to '" +
                                   meta.value("experiment", "") + "'");
    }
    if (Field(m, "resolved_config") != Field(meta, "resolved_config")) {
      Fail(meta_file.string(), "was run with another config (resolved_config differs from " +
                                   (job_dirs.front() / "meta.json").string() + ")");
    }
    for (const char* key : {"git_commit", "build_commit"}) {
      if (Field(m, key) != Field(meta, key)) {
        Fail(meta_file.string(), std::string(key) + " is " + Field(m, key) + ", the first folder's " + Field(meta, key) +
                                     ": the jobs come from different commits");
      }
    }
    // Its jobs, none already merged.
    if (!m.contains("jobs") || !m["jobs"].is_array()) Fail(meta_file.string(), "has no list of jobs");
    std::set<int> own;
    for (const auto& j : m["jobs"]) {
      const int job = JobNumber(j, meta_file, "jobs");
      own.insert(job);
      if (!seen.insert(job).second) {
        Fail(meta_file.string(), "holds job " + std::to_string(job) + ", which an earlier folder holds too");
      }
      jobs.push_back(job);
    }
    // Each table complete: every row of the header's shape, as many rows as meta.json counted,
    // and of the first folder's columns.
    const nlohmann::json counted = m.value("table_rows", nlohmann::json::object());
    for (std::size_t t = 0; t < tables.size(); ++t) {
      const fs::path file = dir / tables[t];
      const std::string text = ReadWholeFile(file);
      std::size_t body = 0;
      const long n = CheckTableRows(file, text, own, &body);
      if (counted.contains(tables[t]) && counted[tables[t]] != n) {
        Fail(file.string(), std::to_string(n) + " rows, its meta.json counted " + counted[tables[t]].dump() +
                                " (an unfinished or altered job?)");
      }
      const std::string h = text.substr(0, body);
      if (headers[t].empty()) {
        headers[t] = h;
      } else if (h != headers[t]) {
        Fail(file.string(), "its columns differ from the first folder's");
      }
      bodies[t] += text.substr(body);
      rows[t] += n;
    }
    wall += m.value("wall_seconds", 0.0);
  }
  // Every sweep point present, unless the merge is partial (runs recorded before meta.json
  // counted the sweep's jobs are not checked).
  if (!options.partial && meta.contains("sweep_jobs") && meta["sweep_jobs"].is_number_integer()) {
    const int total = JobNumber(meta["sweep_jobs"], job_dirs.front() / "meta.json", "sweep_jobs");
    std::string missing;
    int count = 0;
    for (int j = 0; j < total; ++j) {
      if (seen.count(j) == 0) {
        if (++count <= 10) missing += (missing.empty() ? "" : ", ") + std::to_string(j);
      }
    }
    if (count > 0) {
      Fail(out_dir.string(), "the sweep has " + std::to_string(total) + " jobs and " + std::to_string(count) +
                                 " of them are in none of the folders (" + missing + (count > 10 ? ", ..." : "") +
                                 "); nothing merged (give --partial to merge some of a sweep)");
    }
  }
  meta["jobs"] = jobs;
  meta["wall_seconds"] = wall;
  meta["partial"] = options.partial;
  meta["merged_from"] = nlohmann::json::array();
  for (const fs::path& d : job_dirs) meta["merged_from"].push_back(d.string());
  std::vector<std::string> merged(tables.size());
  for (std::size_t t = 0; t < tables.size(); ++t) merged[t] = headers[t] + bodies[t];
  WriteStudyResults(study, out_dir, merged, meta);
}

}  // namespace contactlab
