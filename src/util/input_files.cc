#include "util/input_files.h"

#include <sys/stat.h>

#include <mutex>
#include <string>
#include <vector>

#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

struct InputFile {
  dev_t device = 0;
  ino_t inode = 0;
  fs::path canonical;  // as it was opened
  fs::path given;      // as the command named it, for messages
};

struct Record {
  std::mutex mutex;
  int depth = 0;  // live InputFileRecords
  std::vector<InputFile> files;
};

thread_local int t_cache_entry_writes = 0;

Record& TheRecord() {
  static Record record;
  return record;
}

// PATH made absolute, its symlinks resolved as far as it exists; empty when it cannot be.
fs::path CanonicalOf(const fs::path& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return {};
  const fs::path canonical = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : canonical;
}

}  // namespace

InputFileRecord::InputFileRecord() {
  Record& r = TheRecord();
  const std::lock_guard<std::mutex> lock(r.mutex);
  ++r.depth;
}

InputFileRecord::~InputFileRecord() {
  Record& r = TheRecord();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (--r.depth == 0) r.files.clear();
}

CacheEntryWrite::CacheEntryWrite() { ++t_cache_entry_writes; }
CacheEntryWrite::~CacheEntryWrite() { --t_cache_entry_writes; }

void RecordInputFile(const fs::path& path) {
  Record& r = TheRecord();
  {
    const std::lock_guard<std::mutex> lock(r.mutex);
    if (r.depth == 0) return;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;
  InputFile file{st.st_dev, st.st_ino, CanonicalOf(path), path};
  const std::lock_guard<std::mutex> lock(r.mutex);
  for (const InputFile& f : r.files) {
    if (f.device == file.device && f.inode == file.inode && f.canonical == file.canonical) return;
  }
  r.files.push_back(std::move(file));
}

void CheckOutputIsNoRecordedInput(const fs::path& output, std::string_view what) {
  if (t_cache_entry_writes > 0) return;
  struct stat st {};
  const bool exists = ::stat(output.c_str(), &st) == 0;
  const fs::path canonical = CanonicalOf(output);
  fs::path input;
  {
    Record& r = TheRecord();
    const std::lock_guard<std::mutex> lock(r.mutex);
    for (const InputFile& f : r.files) {
      const bool same_file = exists && f.device == st.st_dev && f.inode == st.st_ino;
      if (same_file || (!canonical.empty() && f.canonical == canonical)) {
        input = f.given;
        break;
      }
    }
  }
  if (input.empty()) return;
  Fail(output.string(), std::string(what) + " is the input " + input.string() +
                            " this command read; refusing to overwrite it");
}

}  // namespace contactlab
