// Shared pieces of the libFuzzer targets (tests/fuzz/README.md): run a loader on the fuzzer's
// bytes, accepting contactlab::Error as the expected outcome of bad input and letting anything
// else (another exception type, a crash, undefined behaviour, a leak) reach libFuzzer.
#pragma once

#include <unistd.h>
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "util/error.h"

namespace contactlab::fuzz {

// Runs LOAD; an Error is bad input correctly refused. Any other exception escapes the fuzz
// target, which libFuzzer reports as a crash ("deadly signal" after std::terminate).
template <typename Load>
void ExpectOnlyError(Load&& load) {
  try {
    load();
  } catch (const contactlab::Error&) {
  }
}

// A per-process file under /tmp for loaders that only read paths; rewritten every iteration.
// SUFFIX is the extension the loader expects (".sdf", ".ps", ".rm").
inline std::filesystem::path WriteScratchFile(std::string_view bytes, std::string_view suffix) {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("contactlab-fuzz-" + std::to_string(::getpid()) + std::string(suffix));
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  if (!out) __builtin_trap();  // the scratch file itself failed: not a finding in the loader
  return path;
}

// The versioned container of util/binary_io.h around PAYLOAD: magic[8] | u32 version |
// u64 payload bytes | payload | u32 CRC-32. Fuzzing the payload behind a valid header and
// checksum lets mutations reach the format's parser instead of stopping at the checksum.
inline std::string WrapInContainer(std::string_view payload, std::string_view magic,
                                   std::uint32_t version) {
  std::string out(8, '\0');
  std::memcpy(out.data(), magic.data(), magic.size() < 8 ? magic.size() : 8);
  const std::uint64_t size = payload.size();
  out.append(reinterpret_cast<const char*>(&version), sizeof version);
  out.append(reinterpret_cast<const char*>(&size), sizeof size);
  out.append(payload);
  const std::uint32_t crc = std::uint32_t(
      crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(payload.data()), uInt(payload.size())));
  out.append(reinterpret_cast<const char*>(&crc), sizeof crc);
  return out;
}

// The file a binary-format target loads: the input as it is when it starts with MAGIC (so the
// container's own checks are fuzzed too), else the input as the payload of a valid container.
inline std::string ContainerBytes(const std::uint8_t* data, std::size_t size, std::string_view magic,
                                  std::uint32_t version) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  if (input.substr(0, magic.size()) == magic) return std::string(input);
  return WrapInContainer(input, magic, version);
}

}  // namespace contactlab::fuzz
