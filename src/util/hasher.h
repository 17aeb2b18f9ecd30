// FNV-1a 64-bit hashing of values and text, for cache keys: deterministic across runs and
// machines of one byte order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace contactlab {

struct Hasher {
  std::uint64_t h = 1469598103934665603ull;
  void Bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void Text(const std::string& s) { Bytes(s.data(), s.size() + 1); }
  template <typename T>
  void Value(const T& v) {
    Bytes(&v, sizeof v);
  }
  std::string Hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

}  // namespace contactlab
