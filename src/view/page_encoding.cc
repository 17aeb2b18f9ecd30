#include "view/page_encoding.h"

#include "util/error.h"

namespace contactlab {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// Value of base64 character C, or -1.
int Sextet(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

std::string Base64Encode(std::string_view bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t(b[i]) << 16) | (std::uint32_t(b[i + 1]) << 8) | b[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    const std::uint32_t v = (std::uint32_t(b[i]) << 16) | (rest == 2 ? std::uint32_t(b[i + 1]) << 8 : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string Base64Decode(std::string_view text, std::string_view where) {
  if (text.size() % 4 != 0) {
    Fail(where, "base64 text of " + std::to_string(text.size()) + " characters (not a multiple of 4)");
  }
  std::string out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    if (pad == 1 && text[i + 2] == '=') Fail(where, "misplaced base64 padding at character " + std::to_string(i + 2));
    int s[4];
    for (int k = 0; k < 4 - pad; ++k) {
      s[k] = Sextet(text[i + k]);
      if (s[k] < 0) {
        Fail(where, "character " + QuoteToken(text.substr(i + k, 1)) + " at " + std::to_string(i + k) +
                        " is not base64");
      }
    }
    for (int k = 4 - pad; k < 4; ++k) s[k] = 0;
    const std::uint32_t v = (std::uint32_t(s[0]) << 18) | (std::uint32_t(s[1]) << 12) | (std::uint32_t(s[2]) << 6) | s[3];
    out += char((v >> 16) & 255);
    if (pad < 2) out += char((v >> 8) & 255);
    if (pad < 1) out += char(v & 255);
  }
  return out;
}

template <class T>
std::vector<T> DecodeArray(std::string_view text, std::string_view where) {
  const std::string bytes = Base64Decode(text, where);
  if (bytes.size() % sizeof(T) != 0) {
    Fail(where, std::to_string(bytes.size()) + " bytes is not a whole number of " + std::to_string(sizeof(T)) +
                    "-byte values");
  }
  std::vector<T> values(bytes.size() / sizeof(T));
  if (!bytes.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

template std::vector<float> DecodeArray<float>(std::string_view, std::string_view);
template std::vector<std::int32_t> DecodeArray<std::int32_t>(std::string_view, std::string_view);
template std::vector<std::uint32_t> DecodeArray<std::uint32_t>(std::string_view, std::string_view);
template std::vector<std::uint8_t> DecodeArray<std::uint8_t>(std::string_view, std::string_view);

std::string ScriptSafeJson(const nlohmann::json& j) {
  const std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

}  // namespace contactlab
