// Compact data for the viewer page (src/view/web/viewer/): binary arrays as base64 text of
// their little-endian bytes, which the page turns back into Float32Array / Uint32Array /
// Uint8Array without parsing numbers, and JSON that can sit inside a <script> element.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace contactlab {

static_assert(std::endian::native == std::endian::little,
              "the viewer page reads typed arrays in little-endian byte order");

// Standard base64 (RFC 4648, '+' '/', '=' padding) of BYTES.
std::string Base64Encode(std::string_view bytes);

// The bytes of base64 TEXT; throws Error("WHERE: ...") on a character outside the alphabet or a
// length that is not a multiple of 4.
std::string Base64Decode(std::string_view text, std::string_view where);

// Base64 of the raw bytes of VALUES (float, std::int32_t, std::uint32_t, std::uint8_t ...).
template <class T>
std::string EncodeArray(const std::vector<T>& values) {
  return Base64Encode(std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

// The inverse of EncodeArray; throws Error naming WHERE when the byte count is not a multiple
// of sizeof(T) or the text is not base64.
template <class T>
std::vector<T> DecodeArray(std::string_view text, std::string_view where);

// J as JSON text that is safe inside <script type="application/json">: every "</" is written
// "<\/" (the same string to a JSON parser), so no value can close the element.
std::string ScriptSafeJson(const nlohmann::json& j);

}  // namespace contactlab
