#include "util/cache_record.h"

#include <system_error>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/hasher.h"

namespace contactlab {
namespace fs = std::filesystem;

std::string CacheRecordOf(const fs::path& entry) {
  // FNV-1a, not a CRC: the entries end with their own CRC-32, and the CRC-32 of any message
  // followed by its CRC is one constant, so a CRC would not tell two entries apart.
  const std::string bytes = ReadWholeFile(entry);
  Hasher h;
  h.Bytes(bytes.data(), bytes.size());
  return "key " + entry.filename().string() + "\nbytes " + std::to_string(bytes.size()) + "\nfnv1a64 " + h.Hex() + "\n";
}

fs::path CacheRecordPath(const fs::path& entry) { return fs::path(entry.string() + ".key"); }

void WriteCacheRecord(const fs::path& entry) { WriteFileAtomically(CacheRecordPath(entry), CacheRecordOf(entry)); }

std::string CacheRecordMismatch(const fs::path& entry) {
  const fs::path record = CacheRecordPath(entry);
  std::error_code ec;
  if (!fs::exists(record, ec)) return "no record of its key (" + record.filename().string() + ")";
  if (ReadWholeFile(record) != CacheRecordOf(entry)) {
    return "its bytes or name differ from its record " + record.filename().string() +
           " (a file of another entry put in its place?)";
  }
  return "";
}

}  // namespace contactlab
