// Joins the results of single-job runs (a cluster array's tasks) into one results folder:
// the rows of cycles.csv and summary.csv concatenated under one header, convergence.csv
// recomputed, meta.json listing every job and folder.
#include <nlohmann/json.hpp>

#include "experiment/convergence_table.h"
#include "experiment/runner.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;

void MergeResults(const std::vector<fs::path>& job_dirs, const fs::path& out_dir) {
  if (job_dirs.empty()) Fail(out_dir.string(), "nothing to merge");
  std::string cycles, summary;
  std::string cycles_header, summary_header;
  nlohmann::json meta;
  std::vector<int> jobs;
  double wall = 0;
  for (const fs::path& dir : job_dirs) {
    for (const char* name : {"cycles.csv", "summary.csv", "meta.json"}) {
      if (!fs::exists(dir / name)) Fail(dir.string(), std::string("is missing ") + name + " (an unfinished job?)");
    }
    // Every folder's table must have the first folder's columns.
    auto take = [&](const char* name, std::string& header, std::string& body) {
      const std::string text = ReadWholeFile(dir / name);
      const auto eol = text.find('\n');
      const std::string h = text.substr(0, eol + 1);
      if (header.empty()) {
        header = h;
      } else if (h != header) {
        Fail((dir / name).string(), "its columns differ from the first folder's");
      }
      body += text.substr(eol + 1);
    };
    take("cycles.csv", cycles_header, cycles);
    take("summary.csv", summary_header, summary);
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
  WriteFileAtomically(out_dir / "cycles.csv", cycles_header + cycles);
  WriteFileAtomically(out_dir / "summary.csv", summary_header + summary);
  WriteFileAtomically(out_dir / "convergence.csv", ConvergenceCsv(summary_header + summary));
  WriteFileAtomically(out_dir / "meta.json", meta.dump(2) + "\n");
}

}  // namespace contactlab
