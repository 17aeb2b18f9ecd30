// CSV as every result table is written and read (RFC 4180): a cell holding a comma, a double
// quote or a line break is written between double quotes, its quotes doubled; the reader takes
// the same quoting back, so a name with a comma (an experiment, a swept scene path, a model)
// stays one cell. Every study's CSV writers, the merge, the readers of cycles.csv and
// summary.csv and the row checks share these two classes.
#pragma once

#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace contactlab {

// One line of a table being written: cells appended to OUT, separated by commas (the caller
// ends the line with '\n').
class CsvLine {
 public:
  explicit CsvLine(std::string* out) : out_(out) {}
  void Text(std::string_view s);
  void Num(const char* format, double v) { Format(format, v); }
  void Int(long long v) { Format("%lld", v); }
  void Empty() { Text({}); }
  // V, or an empty cell when V is negative: a quantity that is never negative and was not
  // measured (no reference, no force), written as every table writes a missing value.
  void NumOrEmpty(const char* format, double v) { v >= 0 ? Format(format, v) : Empty(); }
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
    Text(std::string_view(buf, std::size_t(n)));
  }
  std::string* out_;
  bool first_ = true;
};

// The records of a CSV text, one at a time, as CsvLine writes them: quoted cells may hold
// commas, doubled quotes and line breaks; a line ends with "\n" or "\r\n"; blank lines are
// skipped; a trailing comma ends in an empty cell ("a,b," is "a", "b", ""). TEXT must outlive
// the reader; FILE names it in errors.
class CsvReader {
 public:
  CsvReader(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}
  // The next record's cells into CELLS; false at the end of the text. Throws Error naming the
  // file and line when a quoted cell is not closed (a file cut short) or a closing quote is
  // followed by anything but a comma or the end of the line.
  bool Next(std::vector<std::string>* cells);
  long line() const { return line_; }             // the line the last record starts on, from 1
  std::size_t end() const { return pos_; }        // the offset just past the last record's line break
  const std::string& file() const { return file_; }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  long next_line_ = 1;
  long line_ = 0;
};

// The cells of one CSV record LINE (as CsvReader reads it; an empty line is no cell).
std::vector<std::string> SplitCsvLine(std::string_view line);

}  // namespace contactlab
