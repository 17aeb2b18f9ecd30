// gzip decompression into memory with zlib's inflate (windowBits 16 + 15: gzip wrapper only).
#include "util/gzip_file.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <climits>

#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {

bool IsGzipName(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".gz";
}

std::filesystem::path WithoutGzipSuffix(const std::filesystem::path& path) {
  if (!IsGzipName(path)) return path;
  std::filesystem::path p = path;
  p.replace_extension();
  return p;
}

std::string GunzipBytes(std::string_view bytes, std::string_view file) {
  if (bytes.size() < 2 || static_cast<unsigned char>(bytes[0]) != 0x1f || static_cast<unsigned char>(bytes[1]) != 0x8b) {
    Fail(file, "not a gzip file (no gzip magic bytes 1f 8b at the start)");
  }
  std::string out;
  out.reserve(bytes.size() * 4);
  std::size_t offset = 0;
  // One pass per gzip member (gzip allows several concatenated members).
  while (offset < bytes.size()) {
    z_stream z{};
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) Fail(file, "cannot initialise zlib's inflate");
    int status = Z_OK;
    char buffer[1 << 16];
    while (status != Z_STREAM_END) {
      const std::size_t left = bytes.size() - offset;
      if (z.avail_in == 0 && left > 0) {
        const std::size_t chunk = std::min<std::size_t>(left, UINT_MAX / 2);
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + offset));
        z.avail_in = static_cast<uInt>(chunk);
        offset += chunk;
      }
      z.next_out = reinterpret_cast<Bytef*>(buffer);
      z.avail_out = sizeof(buffer);
      status = inflate(&z, Z_NO_FLUSH);
      out.append(buffer, sizeof(buffer) - z.avail_out);
      if (status == Z_STREAM_END) break;
      if (status == Z_BUF_ERROR && z.avail_in == 0 && offset >= bytes.size()) {
        inflateEnd(&z);
        Fail(file, "truncated gzip data: the compressed stream ends after " + std::to_string(bytes.size()) +
                       " bytes, before its end marker (" + std::to_string(out.size()) + " bytes decompressed)");
      }
      if (status != Z_OK && status != Z_BUF_ERROR) {
        const std::string why = z.msg != nullptr ? z.msg : "zlib error " + std::to_string(status);
        inflateEnd(&z);
        Fail(file, "corrupt gzip data near compressed byte " + std::to_string(offset - z.avail_in) + ": " + why);
      }
    }
    // Bytes the member did not consume belong to the next member (or are trailing zeros).
    offset -= z.avail_in;
    inflateEnd(&z);
    const std::string_view rest = bytes.substr(offset);
    if (std::all_of(rest.begin(), rest.end(), [](char c) { return c == 0; })) break;
    if (rest.size() < 2 || static_cast<unsigned char>(rest[0]) != 0x1f || static_cast<unsigned char>(rest[1]) != 0x8b) {
      Fail(file, "corrupt gzip data: " + std::to_string(rest.size()) + " bytes of garbage after the gzip stream");
    }
  }
  return out;
}

std::string ReadGzipFile(const std::filesystem::path& path) {
  return GunzipBytes(ReadWholeFile(path), path.string());
}

}  // namespace contactlab
