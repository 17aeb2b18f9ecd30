// The record a cache entry is kept with (util/cached_or_built.h): ENTRY.key beside the entry,
// holding the entry's name (its key: the hash of everything it was built from), its size and the
// FNV-1a hash of its bytes. An entry whose record is missing, or names another key or other bytes, is
// not used: a valid file of another entry put in its place (a field of another body, say) would
// otherwise be read as this one.
#pragma once

#include <filesystem>
#include <string>

namespace contactlab {

// The record ENTRY's bytes as they are now would be kept with.
std::string CacheRecordOf(const std::filesystem::path& entry);
// The path of ENTRY's record: ENTRY with ".key" added.
std::filesystem::path CacheRecordPath(const std::filesystem::path& entry);
// Writes ENTRY's record (atomically). Throws Error when it cannot.
void WriteCacheRecord(const std::filesystem::path& entry);
// Empty when ENTRY's record is there and matches its bytes; else why not, for a warning.
std::string CacheRecordMismatch(const std::filesystem::path& entry);

}  // namespace contactlab
