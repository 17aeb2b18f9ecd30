// The one error type of ContactLab: thrown by loading and configuration code, never inside a
// haptic cycle. Its message names the file (and line, record or key) and what is wrong.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace contactlab {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Throws Error("WHERE: WHAT"). WHERE is a file name, optionally with ":line" or a key path.
[[noreturn]] void Fail(std::string_view where, std::string_view what);

// Throws Error("FILE:LINE: WHAT").
[[noreturn]] void FailAtLine(std::string_view file, long line, std::string_view what);

// TOKEN as it may appear inside an error message: at most about 80 characters (longer ones
// are cut with "..." and their length), control bytes and non-ASCII bytes escaped as \xNN, so
// a garbage file or a ten-million-digit number never floods or corrupts the terminal.
std::string QuoteToken(std::string_view token);

}  // namespace contactlab
