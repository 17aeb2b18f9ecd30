#include "util/error.h"

namespace contactlab {

void Fail(std::string_view where, std::string_view what) {
  std::string message(where);
  message += ": ";
  message += what;
  throw Error(message);
}

void FailAtLine(std::string_view file, long line, std::string_view what) {
  Fail(std::string(file) + ":" + std::to_string(line), what);
}

std::string QuoteToken(std::string_view token) {
  constexpr std::size_t kMaxShown = 80;
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  std::size_t shown = 0;
  for (const char c : token) {
    if (shown >= kMaxShown) break;
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f) {
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += c;
    }
    ++shown;
  }
  if (token.size() > kMaxShown) out += "... (" + std::to_string(token.size()) + " characters)";
  return out;
}

}  // namespace contactlab
