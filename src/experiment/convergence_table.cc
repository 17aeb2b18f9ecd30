#include "experiment/convergence_table.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

#include "experiment/metrics.h"
#include "experiment/result_csv.h"

namespace contactlab {

std::string ConvergenceCsv(const std::string& summary_csv) {
  std::istringstream in(summary_csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = SplitCsvLine(line);
  auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : int(it - header.begin());
  };
  const int c_model = col("model"), c_points = col("points"), c_err = col("rms_rel_error"), c_job = col("job");
  // Group by model and the values of every sweep axis except points (the columns between
  // "job" and "model").
  std::map<std::string, std::vector<std::pair<double, double>>> groups;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = SplitCsvLine(line);
    if (int(cells.size()) != int(header.size())) continue;
    std::string key = cells[c_model];
    for (int c = c_job + 1; c < c_model; ++c) {
      if (header[c] != "points") key += ";" + header[c] + "=" + cells[c];
    }
    const double err = std::stod(cells[c_err]);
    if (err >= 0) groups[key].emplace_back(std::stod(cells[c_points]), err);
  }
  std::string out = "group,samples,fitted_order,points,errors\n";
  for (auto& [key, pairs] : groups) {
    std::sort(pairs.begin(), pairs.end());
    std::vector<double> xs, ys;
    std::string pts, errs;
    for (auto [x, y] : pairs) {
      xs.push_back(x), ys.push_back(y);
      char b[48];
      std::snprintf(b, sizeof b, "%s%d", pts.empty() ? "" : " ", int(x));
      pts += b;
      std::snprintf(b, sizeof b, "%s%.4g", errs.empty() ? "" : " ", y);
      errs += b;
    }
    char b[64];
    std::snprintf(b, sizeof b, "%.4g", FittedOrder(xs, ys));
    out += key + "," + std::to_string(pairs.size()) + "," + b + "," + pts + "," + errs + "\n";
  }
  return out;
}

}  // namespace contactlab
