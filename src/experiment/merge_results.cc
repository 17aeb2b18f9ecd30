// Joins the results of single-job runs (a cluster array's tasks) into one results folder: the
// rows of each of the study's tables concatenated under one header (experiment/study.h), its
// derived files recomputed (a contact study's convergence.csv), meta.json listing every job and
// folder.
#include <nlohmann/json.hpp>

#include "experiment/runner.h"
#include "experiment/study.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;

void MergeResults(const std::vector<fs::path>& job_dirs, const fs::path& out_dir) {
  if (job_dirs.empty()) Fail(out_dir.string(), "nothing to merge");
  // The study that wrote the first folder (its meta.json says); every folder must be of it.
  const Study& study = StudyOfResults(job_dirs.front());
  const std::vector<std::string>& tables = study.tables;
  std::vector<std::string> headers(tables.size()), bodies(tables.size());
  nlohmann::json meta;
  std::vector<int> jobs;
  double wall = 0;
  for (const fs::path& dir : job_dirs) {
    if (!fs::exists(dir / "meta.json")) Fail(dir.string(), "is missing meta.json (an unfinished job?)");
    if (const Study& s = StudyOfResults(dir); &s != &study) {
      Fail((dir / "meta.json").string(), "holds a " + s.name + " study, the first folder a " + study.name + " study");
    }
    for (const std::string& name : tables) {
      if (!fs::exists(dir / name)) Fail(dir.string(), "is missing " + name + " (an unfinished job?)");
    }
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
  std::vector<std::string> merged(tables.size());
  for (std::size_t t = 0; t < tables.size(); ++t) merged[t] = headers[t] + bodies[t];
  WriteStudyResults(study, out_dir, merged, meta);
}

}  // namespace contactlab
