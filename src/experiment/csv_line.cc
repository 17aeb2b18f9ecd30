// CSV cells written and read with RFC 4180 quoting (experiment/csv_line.h).
#include "experiment/csv_line.h"

#include "util/error.h"

namespace contactlab {

void CsvLine::Text(std::string_view s) {
  if (!first_) *out_ += ',';
  first_ = false;
  if (s.find_first_of(",\"\n\r") == std::string_view::npos) {
    out_->append(s);
    return;
  }
  *out_ += '"';
  for (const char c : s) {
    if (c == '"') *out_ += '"';
    *out_ += c;
  }
  *out_ += '"';
}

bool CsvReader::Next(std::vector<std::string>* cells) {
  cells->clear();
  // Blank lines between records are skipped.
  while (pos_ < text_.size() && (text_[pos_] == '\n' || text_[pos_] == '\r')) {
    if (text_[pos_] == '\n') ++next_line_;
    ++pos_;
  }
  if (pos_ >= text_.size()) return false;
  line_ = next_line_;
  std::string cell;
  for (;;) {
    // One cell: quoted (up to the closing quote, "" standing for one quote) or plain.
    cell.clear();
    if (pos_ < text_.size() && text_[pos_] == '"') {
      const long opened = next_line_;
      for (++pos_;; ++pos_) {
        if (pos_ >= text_.size()) {
          FailAtLine(file_, opened, "a quoted cell is not closed before the end of the file (cut short?)");
        }
        const char c = text_[pos_];
        if (c == '"' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '"') {
          cell += '"';
          ++pos_;
        } else if (c == '"') {
          ++pos_;
          break;
        } else {
          if (c == '\n') ++next_line_;
          cell += c;
        }
      }
      if (pos_ < text_.size() && text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') ++pos_;
      if (pos_ < text_.size() && text_[pos_] != ',' && text_[pos_] != '\n') {
        FailAtLine(file_, next_line_, "a quoted cell is followed by '" + QuoteToken(text_.substr(pos_, 1)) +
                                          "', not by a comma or the end of the line");
      }
    } else {
      const std::size_t end = text_.find_first_of(",\n", pos_);
      const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
      std::string_view plain = text_.substr(pos_, stop - pos_);
      if (!plain.empty() && plain.back() == '\r' && (stop == text_.size() || text_[stop] == '\n')) {
        plain.remove_suffix(1);
      }
      cell.assign(plain);
      pos_ = stop;
    }
    cells->push_back(cell);
    // A comma starts another cell; a line break or the end of the text ends the record.
    if (pos_ < text_.size() && text_[pos_] == ',') {
      ++pos_;
      continue;
    }
    if (pos_ < text_.size()) {
      ++pos_;  // the '\n'
      ++next_line_;
    }
    return true;
  }
}

std::vector<std::string> SplitCsvLine(std::string_view line) {
  std::vector<std::string> cells;
  CsvReader reader(line, "CSV line");
  reader.Next(&cells);
  return cells;
}

}  // namespace contactlab
