// A versioned binary container with a checksum, shared by every file ContactLab writes
// (distance fields, pointshells, reduced models, caches).
//
// Layout (little-endian):  magic[8] | u32 version | u64 payload bytes | payload | u32 CRC-32
// of the payload (zlib). A wrong magic, an unknown version, a short file, a length mismatch
// or a checksum mismatch is rejected with an Error naming the file.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace contactlab {

class BinaryWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&value);
    bytes_.append(p, sizeof(T));
  }
  template <typename T>
  void PutArray(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    Put<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void PutString(std::string_view s) {
    Put<std::uint64_t>(s.size());
    bytes_.append(s.data(), s.size());
  }
  const std::string& bytes() const { return bytes_; }

  // Writes magic, version, payload and checksum to PATH atomically (util/atomic_file.h).
  // MAGIC is at most 8 characters.
  void Save(const std::filesystem::path& path, std::string_view magic,
            std::uint32_t version) const;

 private:
  std::string bytes_;
};

class BinaryReader {
 public:
  // Reads and checks the container at PATH. Accepts versions 1..MAX_VERSION.
  BinaryReader(const std::filesystem::path& path, std::string_view magic,
               std::uint32_t max_version);

  std::uint32_t version() const { return version_; }
  const std::string& file() const { return file_; }

  template <typename T>
  T Get(std::string_view what) {
    static_assert(std::is_trivially_copyable_v<T>);
    Need(sizeof(T), what);
    T value;
    std::memcpy(&value, payload_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  // Reads an array; MAX_COUNT guards against absurd lengths in a corrupt file.
  template <typename T>
  std::vector<T> GetArray(std::string_view what, std::uint64_t max_count = UINT64_MAX) {
    const auto n = Get<std::uint64_t>(what);
    if (n > max_count || n > (payload_.size() - pos_) / (sizeof(T) > 0 ? sizeof(T) : 1)) {
      Corrupt(std::string(what) + ": array length " + std::to_string(n) + " is impossible");
    }
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), payload_.data() + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
    return values;
  }
  std::string GetString(std::string_view what);
  // Throws unless every payload byte was consumed.
  void ExpectEnd() const;
  [[noreturn]] void Corrupt(const std::string& what) const;

 private:
  void Need(std::size_t n, std::string_view what) const;
  std::string file_;
  std::string payload_;
  std::size_t pos_ = 0;
  std::uint32_t version_ = 0;
};

}  // namespace contactlab
