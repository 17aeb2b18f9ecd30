// The result tables of an experiment run: cycles.csv (one row per cycle per model) and
// summary.csv (one row per model per job), long format. Each table's columns are declared
// once — name, format and the value they show — and drive both the header and the rows, so a
// column cannot be added to one and forgotten in the other. scripts/make_figures.py reads the
// columns by name.
#pragma once

#include <string>
#include <vector>

#include "experiment/runner.h"

namespace contactlab {

// Header line of each table: experiment,job,<sweep axes>,<declared columns>.
std::string CyclesCsvHeader(const ExperimentConfig& config);
std::string SummaryCsvHeader(const ExperimentConfig& config);

// Appends the rows of job result R to OUT.
void AppendCyclesCsv(const ExperimentConfig& config, const JobResult& r, std::string* out);
void AppendSummaryCsv(const ExperimentConfig& config, const JobResult& r, std::string* out);

// Cells of one CSV line (a trailing comma kept: "a,b," splits into "a", "b", "").
std::vector<std::string> SplitCsvLine(const std::string& line);

}  // namespace contactlab
