// The cells of a CSV line (experiment/csv_line.h).
#include "experiment/csv_line.h"

#include <sstream>

namespace contactlab {

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace contactlab
