#include "experiment/studies/contact/convergence_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

#include "experiment/studies/contact/metrics.h"
#include "experiment/studies/contact/result_csv.h"

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
  // Group by model and the values of every sweep axis except points and the pooled ones (the
  // columns between "job" and "model"). A pooled axis (its name ends in "seed": repeated
  // samplings of one configuration) contributes its errors at equal points as one RMS, the
  // expected error of a sampling of that size rather than one draw.
  auto pooled = [](const std::string& name) {
    return name.size() >= 4 && name.compare(name.size() - 4, 4, "seed") == 0;
  };
  std::map<std::string, std::map<double, std::vector<double>>> draws;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = SplitCsvLine(line);
    if (int(cells.size()) != int(header.size())) continue;
    std::string key = cells[c_model];
    for (int c = c_job + 1; c < c_model; ++c) {
      if (header[c] != "points" && !pooled(header[c])) key += ";" + header[c] + "=" + cells[c];
    }
    const double err = std::stod(cells[c_err]);
    if (err >= 0) draws[key][std::stod(cells[c_points])].push_back(err);
  }
  std::map<std::string, std::vector<std::pair<double, double>>> groups;
  for (const auto& [key, by_points] : draws) {
    for (const auto& [n, errs] : by_points) {
      double sq = 0;
      for (double e : errs) sq += e * e;
      groups[key].emplace_back(n, std::sqrt(sq / double(errs.size())));
    }
  }
  std::string out = "group,samples,fitted_order,order_ci95,points,errors\n";
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
    char b[64], ci[64];
    std::snprintf(b, sizeof b, "%.4g", FittedOrder(xs, ys));
    std::snprintf(ci, sizeof ci, "%.4g", FittedOrderHalfWidth95(xs, ys));
    out += key + "," + std::to_string(pairs.size()) + "," + b + "," + ci + "," + pts + "," + errs + "\n";
  }
  return out;
}

}  // namespace contactlab
