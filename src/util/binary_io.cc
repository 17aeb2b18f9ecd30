#include "util/binary_io.h"

#include <zlib.h>

#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr std::size_t kMagicBytes = 8;
constexpr std::size_t kHeaderBytes = kMagicBytes + 4 + 8;

std::string PaddedMagic(std::string_view magic) {
  std::string m(magic.substr(0, kMagicBytes));
  m.resize(kMagicBytes, '\0');
  return m;
}

std::uint32_t Crc32(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const std::size_t chunk = std::min<std::size_t>(bytes.size() - done, 1u << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + done), uInt(chunk));
    done += chunk;
  }
  return std::uint32_t(crc);
}

}  // namespace

void BinaryWriter::Save(const std::filesystem::path& path, std::string_view magic,
                        std::uint32_t version) const {
  const std::uint64_t size = bytes_.size();
  const std::uint32_t crc = Crc32(bytes_);
  WriteFileAtomically(
      path,
      [&](std::ostream& out) {
        const std::string m = PaddedMagic(magic);
        out.write(m.data(), kMagicBytes);
        out.write(reinterpret_cast<const char*>(&version), sizeof version);
        out.write(reinterpret_cast<const char*>(&size), sizeof size);
        out.write(bytes_.data(), std::streamsize(bytes_.size()));
        out.write(reinterpret_cast<const char*>(&crc), sizeof crc);
      },
      true);
}

BinaryReader::BinaryReader(const std::filesystem::path& path, std::string_view magic,
                           std::uint32_t max_version)
    : file_(path.string()) {
  std::string all = ReadWholeFile(path);
  if (all.size() < kHeaderBytes + 4) {
    Fail(file_, "truncated: " + std::to_string(all.size()) + " bytes is shorter than a header");
  }
  if (all.compare(0, kMagicBytes, PaddedMagic(magic)) != 0) {
    Fail(file_, "not a " + std::string(magic) + " file (wrong magic bytes)");
  }
  std::memcpy(&version_, all.data() + kMagicBytes, 4);
  std::uint64_t size = 0;
  std::memcpy(&size, all.data() + kMagicBytes + 4, 8);
  if (version_ == 0 || version_ > max_version) {
    Fail(file_, "unsupported format version " + std::to_string(version_) + " (this build reads up to " +
                    std::to_string(max_version) + ")");
  }
  if (size != all.size() - kHeaderBytes - 4) {
    Fail(file_, "truncated or padded: header promises " + std::to_string(size) +
                    " payload bytes, file holds " +
                    std::to_string(all.size() >= kHeaderBytes + 4 ? all.size() - kHeaderBytes - 4 : 0));
  }
  std::uint32_t stored_crc = 0;
  std::memcpy(&stored_crc, all.data() + kHeaderBytes + size, 4);
  payload_ = all.substr(kHeaderBytes, size);
  if (Crc32(payload_) != stored_crc) Fail(file_, "checksum mismatch: the file is corrupt");
}

std::string BinaryReader::GetString(std::string_view what) {
  const auto n = Get<std::uint64_t>(what);
  Need(n, what);
  std::string s = payload_.substr(pos_, n);
  pos_ += n;
  return s;
}

void BinaryReader::ExpectEnd() const {
  if (pos_ != payload_.size()) Corrupt("unexpected trailing payload bytes");
}

void BinaryReader::Corrupt(const std::string& what) const { Fail(file_, "corrupt: " + what); }

void BinaryReader::Need(std::size_t n, std::string_view what) const {
  if (n > payload_.size() - pos_) Corrupt("payload ends while reading " + std::string(what));
}

}  // namespace contactlab
