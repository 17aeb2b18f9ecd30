// One line of a result table being written (cells appended with their printf formats) and the
// cells of a line read back: what every study's CSV writers and the merge share.
#pragma once

#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace contactlab {

// One line of a table being written: cells appended to OUT, separated by commas.
class CsvLine {
 public:
  explicit CsvLine(std::string* out) : out_(out) {}
  void Text(std::string_view s) { Cell(s.data(), s.size()); }
  void Num(const char* format, double v) { Format(format, v); }
  void Int(long long v) { Format("%lld", v); }
  void Empty() { Cell("", 0); }
  // One cell of VALUES each printed with FORMAT, separated by spaces (empty cell for none).
  void Numbers(const char* format, std::span<const double> values) {
    if (!first_) *out_ += ',';
    first_ = false;
    char buf[64];
    for (std::size_t j = 0; j < values.size(); ++j) {
      if (j > 0) *out_ += ' ';
      const int n = std::snprintf(buf, sizeof buf, format, values[j]);
      out_->append(buf, std::size_t(n));
    }
  }

 private:
  template <class T>
  void Format(const char* format, T v) {
    char buf[64];
    const int n = std::snprintf(buf, sizeof buf, format, v);
    Cell(buf, std::size_t(n));
  }
  void Cell(const char* s, std::size_t n) {
    if (!first_) *out_ += ',';
    out_->append(s, n);
    first_ = false;
  }
  std::string* out_;
  bool first_ = true;
};

// Cells of one CSV line (a trailing comma kept: "a,b," splits into "a", "b", "").
std::vector<std::string> SplitCsvLine(const std::string& line);

}  // namespace contactlab
