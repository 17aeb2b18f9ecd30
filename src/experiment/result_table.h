// A study's result tables declared once (experiment/study.h): each table's file and its columns,
// every column with its name, unit and meaning beside the function that writes its cell. The
// header line, the rows, meta.json's "columns" and `contactlab columns` all come from that one
// declaration, so a writer cannot write a column it does not declare nor leave one out, and the
// figure scripts (scripts/figures/common.py) name columns the program declares.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/csv_line.h"
#include "experiment/experiment_config.h"

namespace contactlab {

// One declared column.
struct ResultColumn {
  std::string name;
  std::string unit;     // SI unit ("m", "N", "us", ...); "" for counts, labels, flags and ratios
  std::string meaning;  // one line: what the value is
};

// Which leading columns a table's rows carry before its declared columns. A sweep axis is a
// column named as the config's sweep names it ("scene", "trajectory.speed"), except one named
// like a column the table declares ("points", the model's own count): that axis is written
// "sweep.points", as the config spells it, so every header is unique.
enum class TableKeys {
  kNone,              // none: the declared columns alone (a table derived from another)
  kJobAndAllAxes,     // experiment, job, then every sweep axis of the config
  kJobAndOtherAxes,   // experiment, job, then the sweep axes not named like a declared column
};

// The prefix of a sweep axis column named like a declared column.
inline const std::string kSweepColumnPrefix = "sweep.";

struct ResultTable {
  std::string file;     // e.g. "summary.csv"
  std::string meaning;  // what one row is
  TableKeys keys = TableKeys::kJobAndAllAxes;
  std::vector<ResultColumn> columns;  // in file order, after the keys

  // The declared column of that NAME, or null.
  const ResultColumn* Find(const std::string& name) const;
  // NAME, for a reader naming a column it reads; a name the table does not declare is a
  // programming error (std::logic_error).
  const std::string& Column(const std::string& name) const;
  // The column holding sweep axis AXIS in this table (AXIS, or "sweep." AXIS when the table
  // declares a column of that name).
  std::string AxisColumn(const std::string& axis) const;
  // The header line (with its line break) of the table written for CONFIG.
  std::string Header(const ExperimentConfig& config) const;
  // Appends the key cells of a row of JOB of CONFIG to LINE (nothing for TableKeys::kNone).
  void AppendKeys(const ExperimentConfig& config, const Job& job, CsvLine* line) const;
};

// The key columns every job's table begins with (TableKeys other than kNone), before the sweep
// axes: experiment and job.
const std::vector<ResultColumn>& JobKeyColumns();

// TABLE's columns as meta.json and `contactlab columns --json` write them: an array of
// {"name", "unit", "meaning"}, the key columns first (the sweep axes, which depend on the config,
// are not listed: the config's sweep names them).
nlohmann::json ColumnsJson(const ResultTable& table);

// A column as its writer holds it: the declaration and how a ROW's cell is written.
template <class Row>
struct TableColumn {
  const char* name;
  const char* unit;
  const char* meaning;
  void (*write)(const Row&, CsvLine&);
};

// The declaration of a table whose columns are COLUMNS (a writer's array of TableColumn, or of
// any column type with the same name, unit, meaning and write members).
template <class Column, std::size_t N>
ResultTable DeclareTable(std::string file, std::string meaning, TableKeys keys, const Column (&columns)[N]) {
  ResultTable t{std::move(file), std::move(meaning), keys, {}};
  for (const Column& c : columns) t.columns.push_back({c.name, c.unit, c.meaning});
  return t;
}

// Appends ROW's declared cells to LINE, in COLUMNS' order.
template <class Column, std::size_t N, class Row>
void AppendCells(const Column (&columns)[N], const Row& row, CsvLine* line) {
  for (const Column& c : columns) c.write(row, *line);
}

}  // namespace contactlab
