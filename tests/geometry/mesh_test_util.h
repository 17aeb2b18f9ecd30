// Helpers for the mesh I/O tests: writing hand-made fixture files (text or bytes, either
// endianness) into a TempDir, and checking that loading fails with a message naming the place.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include "geometry/mesh_io.h"
#include "util/error.h"

namespace contactlab::testing {

// Writes BYTES to PATH verbatim and returns PATH.
inline std::filesystem::path WriteFixture(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path;
}

// Builds binary fixture bytes in little- or big-endian order.
class ByteBuilder {
 public:
  explicit ByteBuilder(bool big_endian = false) : big_endian_(big_endian) {}
  template <typename T>
  ByteBuilder& Put(T v) {
    char raw[sizeof(T)];
    std::memcpy(raw, &v, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
    bytes_.append(raw, sizeof(T));
    return *this;
  }
  ByteBuilder& Text(const std::string& s) {
    bytes_ += s;
    return *this;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  bool big_endian_;
  std::string bytes_;
};

// Loads PATH expecting an Error whose message contains every string of PARTS.
inline void ExpectLoadError(const std::filesystem::path& path, std::initializer_list<std::string> parts) {
  try {
    LoadMesh(path);
    ADD_FAILURE() << "loading " << path << " did not throw";
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "message '" << message << "' lacks '" << part << "'";
    }
  }
}

}  // namespace contactlab::testing
