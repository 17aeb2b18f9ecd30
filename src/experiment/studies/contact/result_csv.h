// The contact study's result tables: cycles.csv (one row per cycle per model) and summary.csv
// (one row per model per job), long format. Each table's columns are declared once — name,
// unit, meaning, format and the value they show (experiment/result_table.h) — and drive the
// header, the rows and meta.json's "columns", so a column cannot be added to one and forgotten
// in another. cycles.csv is read back by the same table (ReadCyclesCsv, for the viewer's
// replay); scripts/figures/ name the columns through the declarations (`contactlab columns`).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "experiment/csv_line.h"
#include "experiment/result_table.h"
#include "experiment/studies/contact/contact_study.h"

namespace contactlab {

// The declarations of the tables (the study's `tables`, experiment/study.h).
const ResultTable& CyclesTable();
const ResultTable& SummaryTable();

// Header line of each table: experiment,job,<sweep axes>,<declared columns>.
std::string CyclesCsvHeader(const ExperimentConfig& config);
std::string SummaryCsvHeader(const ExperimentConfig& config);

// Appends the rows of job result R to OUT.
void AppendCyclesCsv(const ExperimentConfig& config, const JobResult& r, std::string* out);
void AppendSummaryCsv(const ExperimentConfig& config, const JobResult& r, std::string* out);

// One row of cycles.csv read back: the job's own columns, and a CycleRow's values. The model
// name and the reduced coordinates are held here (a CycleRow only views them).
struct CyclesCsvRow {
  long line = 0;                         // line in the file (1: the header)
  std::string experiment;
  int job = 0;
  std::vector<std::string> axis_values;  // one per sweep axis, in ReadCyclesCsv's order
  std::string model;
  std::vector<double> q, q_B;            // A's and B's reduced coordinates (empty: a rigid body)
  // Every other column; its job, model, q and q_B are left unset (they are above). Empty cells
  // read as has_reference = false, deformable = false and zero step times.
  CycleRow values;

  // The row as AppendCyclesCsv takes it: VALUES with the job, model and coordinates above. It
  // views this record's model and vectors: valid while the record lives unchanged.
  CycleRow row() const;
};

// Reads cycles.csv FILE (as AppendCyclesCsv writes it), calling ON_ROW with each row in the
// file's order (the record is reused: copy what you keep); blank lines are skipped. Columns are
// found by name from the writer's table, every one of them required; a cell of numbers is read
// to doubles once. Returns the names of the sweep axes (header cells that are no column).
// Throws Error naming the file (and the line and column where there is one) for: an empty
// file, a missing column, a row whose number of cells differs from the header's, a cell that
// is not a number (an integer for job, cycle, contacts, nodes, level), and a q or q_B cell
// whose length differs from the first row of the same job and model.
std::vector<std::string> ReadCyclesCsv(const std::filesystem::path& file,
                                       const std::function<void(const CyclesCsvRow&)>& on_row);

}  // namespace contactlab
