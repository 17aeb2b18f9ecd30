// Joins the results of single-job runs (a cluster array's tasks) into one results folder:
// the rows of cycles.csv and summary.csv concatenated under one header, convergence.csv
// recomputed, meta.json listing every job and folder; for a deformed-field study the rows of
// field_error.csv and field_slice.csv.
#include <nlohmann/json.hpp>

#include "experiment/convergence_table.h"
#include "experiment/runner.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;

void MergeResults(const std::vector<fs::path>& job_dirs, const fs::path& out_dir) {
  if (job_dirs.empty()) Fail(out_dir.string(), "nothing to merge");
  // A contact study's tables, or a deformed-field study's (the first folder says which).
  const bool field_study = fs::exists(job_dirs.front() / "field_error.csv");
  const std::vector<std::string> tables = field_study ? std::vector<std::string>{"field_error.csv", "field_slice.csv"}
                                                      : std::vector<std::string>{"cycles.csv", "summary.csv"};
  std::vector<std::string> headers(tables.size()), bodies(tables.size());
  nlohmann::json meta;
  std::vector<int> jobs;
  double wall = 0;
  for (const fs::path& dir : job_dirs) {
    for (const std::string& name : tables) {
      if (!fs::exists(dir / name)) Fail(dir.string(), "is missing " + name + " (an unfinished job?)");
    }
    if (!fs::exists(dir / "meta.json")) Fail(dir.string(), "is missing meta.json (an unfinished job?)");
    // Every folder's table must have the first folder's columns.
    for (std::size_t t = 0; t < tables.size(); ++t) {
      const std::string text = ReadWholeFile(dir / tables[t]);
      const auto eol = text.find('\n');
      const std::string h = text.substr(0, eol + 1);
      if (headers[t].empty()) {
        headers[t] = h;
      } else if (h != headers[t]) {
        Fail((dir / tables[t]).string(), "its columns differ from the first folder's");
      }
      bodies[t] += text.substr(eol + 1);
    }
    nlohmann::json m;
    try {
      m = nlohmann::json::parse(ReadWholeFile(dir / "meta.json"));
    } catch (const nlohmann::json::exception& e) {
      Fail((dir / "meta.json").string(), std::string("not valid JSON: ") + e.what());
    }
    if (meta.is_null()) meta = m;
    if (m.value("experiment", "") != meta.value("experiment", "")) {
      Fail((dir / "meta.json").string(), "belongs to another experiment");
    }
    for (int j : m["jobs"]) jobs.push_back(j);
    wall += m.value("wall_seconds", 0.0);
  }
  meta["jobs"] = jobs;
  meta["wall_seconds"] = wall;
  meta["merged_from"] = nlohmann::json::array();
  for (const fs::path& d : job_dirs) meta["merged_from"].push_back(d.string());
  fs::create_directories(out_dir);
  for (std::size_t t = 0; t < tables.size(); ++t) WriteFileAtomically(out_dir / tables[t], headers[t] + bodies[t]);
  if (!field_study) WriteFileAtomically(out_dir / "convergence.csv", ConvergenceCsv(headers[1] + bodies[1]));
  WriteFileAtomically(out_dir / "meta.json", meta.dump(2) + "\n");
}

}  // namespace contactlab
