// A line-by-line tokenizer over a text file held in memory, for the text mesh readers (OBJ,
// OFF, ASCII STL and PLY): std::from_chars on string views, no streams, errors name FILE:LINE.
// A token or line of the file quoted in an error goes through QuoteToken (util/error.h): cut
// to a readable length, control and non-ASCII bytes escaped.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include "util/error.h"

namespace contactlab::internal {

class LineScanner {
 public:
  // TEXT must outlive the scanner. FILE names the file in error messages. Line numbers count
  // from FIRST_LINE (for a body that starts after a header).
  LineScanner(std::string_view text, std::string_view file, long first_line = 1)
      : text_(text), file_(file), line_number_(first_line - 1) {}

  // Moves to the next line (without its "\n" or "\r\n"); false at the end of the text.
  bool NextLine() {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line_ = text_.substr(pos_, end - pos_);
    if (!line_.empty() && line_.back() == '\r') line_.remove_suffix(1);
    pos_ = end + 1;
    ++line_number_;
    cursor_ = 0;
    return true;
  }

  // Moves to the next line holding a token that is not a '#' comment; false at the end.
  bool NextContentLine() {
    while (NextLine()) {
      if (!AtLineEnd()) return true;
    }
    return false;
  }

  // True when only blanks (or a '#' comment) remain on the current line.
  bool AtLineEnd() {
    SkipBlanks();
    return cursor_ >= line_.size() || line_[cursor_] == '#';
  }

  // The next blank-separated token of the current line; empty at the end of the line or at
  // a '#' comment.
  std::string_view NextToken() {
    if (AtLineEnd()) {
      cursor_ = line_.size();
      return {};
    }
    const std::size_t begin = cursor_;
    while (cursor_ < line_.size() && !IsBlank(line_[cursor_])) ++cursor_;
    return line_.substr(begin, cursor_ - begin);
  }

  // Reads a finite floating-point number; WHAT names it in the error message.
  double ReadDouble(std::string_view what) {
    const std::string_view token = NextToken();
    if (token.empty()) Fail("expected " + std::string(what) + ", found end of line");
    double value = 0;
    if (!ParseDouble(token, &value)) {
      Fail("expected " + std::string(what) + ", found '" + QuoteToken(token) + "'");
    }
    if (!std::isfinite(value)) {
      Fail(std::string(what) + " is not finite: '" + QuoteToken(token) + "'");
    }
    return value;
  }

  // Reads an integer; WHAT names it in the error message.
  long long ReadInt(std::string_view what) {
    const std::string_view token = NextToken();
    if (token.empty()) Fail("expected " + std::string(what) + ", found end of line");
    long long value = 0;
    if (!ParseInt(token, &value)) {
      Fail("expected " + std::string(what) + " (an integer), found '" + QuoteToken(token) + "'");
    }
    return value;
  }

  // Skips one token, failing when the line has none left.
  void SkipToken(std::string_view what) {
    if (NextToken().empty()) Fail("expected " + std::string(what) + ", found end of line");
  }

  [[noreturn]] void Fail(const std::string& what) const { FailAtLine(file_, line_number_, what); }

  long line_number() const { return line_number_; }
  std::string_view line() const { return line_; }
  // Byte offset of the start of the next line in TEXT; TEXT's size after a last line without
  // a line break (never past the end).
  std::size_t offset() const { return pos_ < text_.size() ? pos_ : text_.size(); }

  // Parses a whole token as a number ('+' sign and out-of-range magnitudes allowed:
  // overflow gives +-inf, underflow 0 or a denormal). False when TOKEN is not a number.
  static bool ParseDouble(std::string_view token, double* value) {
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
    if (ptr != end) return false;
    if (ec == std::errc::result_out_of_range) {
      *value = std::strtod(std::string(token).c_str(), nullptr);
      return true;
    }
    return ec == std::errc();
  }

  static bool ParseInt(std::string_view token, long long* value) {
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
    return ec == std::errc() && ptr == end;
  }

 private:
  static bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void SkipBlanks() {
    while (cursor_ < line_.size() && IsBlank(line_[cursor_])) ++cursor_;
  }

  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;  // start of the next line
  std::string_view line_;
  std::size_t cursor_ = 0;  // within line_
  long line_number_ = 0;
};

}  // namespace contactlab::internal
