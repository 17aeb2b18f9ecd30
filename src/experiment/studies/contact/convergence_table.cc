#include "experiment/studies/contact/convergence_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

#include "experiment/csv_line.h"
#include "experiment/studies/contact/metrics.h"
#include "experiment/studies/contact/result_csv.h"

namespace contactlab {
namespace {

// One group's fit.
struct ConvergenceRow {
  std::string group;
  std::size_t samples = 0;
  double fitted_order = 0, order_ci95 = 0;
  std::string points, errors;  // space-separated, by points
};

const TableColumn<ConvergenceRow> kConvergenceColumns[] = {
    {"group", "", "the model and the values of the sweep axes other than points and *seed (model;axis=value...)",
     [](const ConvergenceRow& r, CsvLine& l) { l.Text(r.group); }},
    {"samples", "", "pointshell sizes in the fit",
     [](const ConvergenceRow& r, CsvLine& l) { l.Int((long long)r.samples); }},
    {"fitted_order", "", "fitted order: error ~ points^-order (least squares in log-log)",
     [](const ConvergenceRow& r, CsvLine& l) { l.Num("%.4g", r.fitted_order); }},
    {"order_ci95", "", "95 % confidence half-width of fitted_order",
     [](const ConvergenceRow& r, CsvLine& l) { l.Num("%.4g", r.order_ci95); }},
    {"points", "", "the pointshell sizes, space-separated, ascending",
     [](const ConvergenceRow& r, CsvLine& l) { l.Text(r.points); }},
    {"errors", "", "rms_rel_error at each size (RMS over pooled *seed axes), space-separated",
     [](const ConvergenceRow& r, CsvLine& l) { l.Text(r.errors); }},
};

}  // namespace

const ResultTable& ConvergenceTable() {
  static const ResultTable table = DeclareTable("convergence.csv", "one row per model and combination of the other sweep axes",
                                                TableKeys::kNone, kConvergenceColumns);
  return table;
}

std::string ConvergenceCsv(const std::string& summary_csv) {
  CsvReader reader(summary_csv, "summary.csv");
  std::vector<std::string> header, cells;
  reader.Next(&header);
  auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : int(it - header.begin());
  };
  const ResultTable& summary = SummaryTable();
  const int c_model = col(summary.Column("model")), c_points = col(summary.Column("points")),
            c_err = col(summary.Column("rms_rel_error")), c_job = col(summary.Column("job"));
  // Group by model and the values of every sweep axis except points and the pooled ones (the
  // columns between "job" and "model"). A pooled axis (its name ends in "seed": repeated
  // samplings of one configuration) contributes its errors at equal points as one RMS, the
  // expected error of a sampling of that size rather than one draw.
  auto pooled = [](const std::string& name) {
    return name.size() >= 4 && name.compare(name.size() - 4, 4, "seed") == 0;
  };
  std::map<std::string, std::map<double, std::vector<double>>> draws;
  while (reader.Next(&cells)) {
    if (int(cells.size()) != int(header.size())) continue;
    std::string key = cells[c_model];
    for (int c = c_job + 1; c < c_model; ++c) {
      if (header[c] != summary.AxisColumn("points") && !pooled(header[c])) key += ";" + header[c] + "=" + cells[c];
    }
    // An empty error (no reference) or points (a model that reads no pointshell): no draw.
    if (cells[c_err].empty() || cells[c_points].empty()) continue;
    draws[key][std::stod(cells[c_points])].push_back(std::stod(cells[c_err]));
  }
  std::map<std::string, std::vector<std::pair<double, double>>> groups;
  for (const auto& [key, by_points] : draws) {
    for (const auto& [n, errs] : by_points) {
      double sq = 0;
      for (double e : errs) sq += e * e;
      groups[key].emplace_back(n, std::sqrt(sq / double(errs.size())));
    }
  }
  std::string out = ConvergenceTable().Header(ExperimentConfig());
  for (auto& [key, pairs] : groups) {
    std::sort(pairs.begin(), pairs.end());
    std::vector<double> xs, ys;
    ConvergenceRow row;
    row.group = key;
    row.samples = pairs.size();
    for (auto [x, y] : pairs) {
      xs.push_back(x), ys.push_back(y);
      char b[48];
      std::snprintf(b, sizeof b, "%s%d", row.points.empty() ? "" : " ", int(x));
      row.points += b;
      std::snprintf(b, sizeof b, "%s%.4g", row.errors.empty() ? "" : " ", y);
      row.errors += b;
    }
    row.fitted_order = FittedOrder(xs, ys);
    row.order_ci95 = FittedOrderHalfWidth95(xs, ys);
    CsvLine line(&out);
    AppendCells(kConvergenceColumns, row, &line);
    out += '\n';
  }
  return out;
}

}  // namespace contactlab
