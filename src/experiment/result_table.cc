// Result tables declared once (experiment/result_table.h).
#include "experiment/result_table.h"

#include <stdexcept>

namespace contactlab {

const ResultColumn* ResultTable::Find(const std::string& name) const {
  for (const ResultColumn& c : columns) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

const std::string& ResultTable::Column(const std::string& name) const {
  if (const ResultColumn* c = Find(name)) return c->name;
  for (const ResultColumn& c : JobKeyColumns()) {
    if (keys != TableKeys::kNone && c.name == name) return c.name;
  }
  throw std::logic_error(file + " declares no column '" + name + "'");
}

std::string ResultTable::Header(const ExperimentConfig& config) const {
  std::string h;
  CsvLine line(&h);
  if (keys != TableKeys::kNone) {
    for (const ResultColumn& c : JobKeyColumns()) line.Text(c.name);
    for (const SweepAxis& a : config.sweep) {
      if (Find(a.name) == nullptr) {
        line.Text(a.name);
      } else if (keys == TableKeys::kJobAndAllAxes) {
        line.Text(kSweepColumnPrefix + a.name);
      }
    }
  }
  for (const ResultColumn& c : columns) line.Text(c.name);
  return h + "\n";
}

void ResultTable::AppendKeys(const ExperimentConfig& config, const Job& job, CsvLine* line) const {
  if (keys == TableKeys::kNone) return;
  line->Text(config.name);
  line->Int(job.index);
  for (const auto& [axis, value] : job.axis_values) {
    if (keys == TableKeys::kJobAndAllAxes || Find(axis) == nullptr) line->Text(value);
  }
}

std::string ResultTable::AxisColumn(const std::string& axis) const {
  return Find(axis) == nullptr ? axis : kSweepColumnPrefix + axis;
}

const std::vector<ResultColumn>& JobKeyColumns() {
  static const std::vector<ResultColumn> keys = {
      {"experiment", "", "the experiment's name (its config's name:)"},
      {"job", "", "the job's index in the config's expanded sweep, from 0; the sweep axes' values follow"},
  };
  return keys;
}

nlohmann::json ColumnsJson(const ResultTable& table) {
  nlohmann::json columns = nlohmann::json::array();
  auto add = [&](const ResultColumn& c) {
    columns.push_back({{"name", c.name}, {"unit", c.unit}, {"meaning", c.meaning}});
  };
  if (table.keys != TableKeys::kNone) {
    for (const ResultColumn& c : JobKeyColumns()) add(c);
  }
  for (const ResultColumn& c : table.columns) add(c);
  return columns;
}

}  // namespace contactlab
