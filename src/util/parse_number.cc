#include "util/parse_number.h"

#include <charconv>
#include <cmath>

#include "util/error.h"

namespace contactlab {
namespace {

std::string_view Trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string_view::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

template <typename T>
std::optional<T> Parse(std::string_view text) {
  text = Trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) return std::nullopt;
  }
  return value;
}

}  // namespace

std::optional<double> ParseDouble(std::string_view text) { return Parse<double>(text); }

std::optional<long long> ParseInteger(std::string_view text) { return Parse<long long>(text); }

std::vector<double> ParseNumberList(std::string_view text, std::string_view where) {
  std::vector<double> values;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t comma = text.find(',', pos);
    const std::string_view item = text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
    const std::optional<double> v = ParseDouble(item);
    if (!v) {
      std::string what(1, '\'');
      what.append(Trim(item));
      what.append("' is not a finite number");
      Fail(where, what);
    }
    values.push_back(*v);
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  return values;
}

}  // namespace contactlab
