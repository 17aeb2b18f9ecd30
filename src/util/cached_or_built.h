// A value read from its cache file when a good one is there, and otherwise built and saved:
// the scene's fields, pointshells and reduced models (scene/scene_assets.cc) and what
// models derive from a field (an inner-sphere packing, ContactBody::DerivedCachePath).
#pragma once

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>

#include "util/cache_record.h"
#include "util/error.h"
#include "util/input_files.h"

namespace contactlab {

// Reads T from CACHED with LOAD when CACHED is not empty and names a good entry; otherwise
// BUILDs it and, when CACHED is not empty, SAVEs it there with its record (util/cache_record.h;
// its folder made first; a save that fails with Error is reported on stderr and the built value
// returned all the same). A bad entry (truncated, corrupt, from another version: LOAD throws
// Error; or its record missing or not its own) is reported on stderr and rebuilt. VERBOSE: says
// on stderr which it did, naming WHAT.
template <typename T, typename Load, typename Save, typename Build>
std::shared_ptr<const T> CachedOrBuilt(const std::filesystem::path& cached, bool verbose, const std::string& what,
                                       Load load, Save save, Build build) {
  std::error_code ec;
  if (!cached.empty() && std::filesystem::exists(cached, ec)) {
    try {
      if (const std::string why = CacheRecordMismatch(cached); !why.empty()) Fail(cached.string(), why);
      auto value = std::make_shared<const T>(load(cached));
      if (verbose) std::cerr << "reusing " << what << " from " << cached.string() << "\n";
      return value;
    } catch (const Error& e) {
      std::cerr << "warning: ignoring a bad cache entry: " << e.what() << "\n";
    }
  }
  if (verbose) std::cerr << "building " << what << "\n";
  auto value = std::make_shared<const T>(build());
  if (!cached.empty()) {
    // The cache serves speed only: a cache folder that cannot take the entry (read-only, full,
    // not a folder) is reported and the value used as built, never a failed command.
    try {
      std::filesystem::create_directories(cached.parent_path(), ec);
      const CacheEntryWrite cache_entry;  // another job may have read the entry another job saved
      save(*value, cached);
      WriteCacheRecord(cached);
    } catch (const Error& e) {
      std::cerr << "warning: not cached (" << e.what() << "); going on without the cache\n";
    }
  }
  return value;
}

}  // namespace contactlab
