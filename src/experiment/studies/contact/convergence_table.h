// convergence.csv: for each model and each combination of the sweep axes other than
// "points", the error against the reference as the pointshell grows and the fitted order
// (error ~ points^-order, metrics.h FittedOrder) with its 95 % confidence half-width. Axes
// whose name ends in "seed" are pooled: their errors at equal points combine as one RMS. Computed from summary.csv text, so a merged
// run gets the same table as a local one.
#pragma once

#include <string>

#include "experiment/result_table.h"

namespace contactlab {

// The declaration of convergence.csv (a table derived from summary.csv: no job keys).
const ResultTable& ConvergenceTable();

// The convergence table (with header) of SUMMARY_CSV (with header). Rows without a reference
// (rms_rel_error < 0) are left out.
std::string ConvergenceCsv(const std::string& summary_csv);

}  // namespace contactlab
