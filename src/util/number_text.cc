#include "util/number_text.h"

#include <charconv>
#include <cmath>

namespace contactlab {
namespace {

template <typename T>
void Append(T v, std::string* out, std::string_view what) {
  RequireFinite(double(v), what);
  char buffer[32];
  // Shortest round-trip digits in %g style: an integer-valued 2e21 is 2e+21, not all its digits.
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), v, std::chars_format::general);
  out->append(buffer, ptr);
}

}  // namespace

void RequireFinite(double v, std::string_view what) {
  if (std::isfinite(v)) return;
  throw NonFiniteValue(std::string(what) + " is " + (std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf") +
                       ", not a finite number; nothing written");
}

void AppendNumber(double v, std::string* out, std::string_view what) { Append(v, out, what); }
void AppendNumber(float v, std::string* out, std::string_view what) { Append(v, out, what); }

std::string NumberText(double v, std::string_view what) {
  std::string s;
  Append(v, &s, what);
  return s;
}

std::string NumberText(float v, std::string_view what) {
  std::string s;
  Append(v, &s, what);
  return s;
}

void AppendNumbers(std::span<const double> values, char separator, std::string* out, std::string_view what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) *out += separator;
    Append(values[i], out, what);
  }
}

}  // namespace contactlab
