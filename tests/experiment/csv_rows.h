// A results table read back as the figures read it: one column -> cell map per row, the header
// naming the columns; a row whose cell count differs from the header's fails the test.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "experiment/studies/contact/result_csv.h"
#include "util/atomic_file.h"

namespace contactlab::testing {

inline std::vector<std::map<std::string, std::string>> ReadCsvRows(const std::filesystem::path& file) {
  std::istringstream in(ReadWholeFile(file));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = SplitCsvLine(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = SplitCsvLine(line);
    EXPECT_EQ(cells.size(), header.size()) << file << ": " << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace contactlab::testing
