#include "util/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "util/error.h"
#include "util/output_target.h"
#include "util/temporary_files.h"

namespace contactlab {
namespace fs = std::filesystem;

TemporaryOutput::TemporaryOutput(fs::path path) : path_(std::move(path)) {
  CheckOutputTarget(path_, "the output");
  // Unique per process and per call, so threads writing the same target never collide.
  static std::atomic<unsigned> counter{0};
  temporary_ = path_.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  std::error_code ec;
  if (path_.has_parent_path() && !fs::exists(path_.parent_path(), ec)) {
    fs::create_directories(path_.parent_path(), ec);
    if (ec) Fail(path_.string(), "cannot create the output folder: " + ec.message());
  }
  slot_ = RegisterTemporaryFile(temporary_.c_str());
}

TemporaryOutput::~TemporaryOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
  UnregisterTemporaryFile(slot_);
}

void TemporaryOutput::Commit() {
  // The target may have been replaced by something else while we wrote.
  CheckOutputTarget(path_, "the output");
  std::error_code ec;
  fs::rename(temporary_, path_, ec);
  if (ec) Fail(path_.string(), "cannot rename the finished temporary file: " + ec.message());
  committed_ = true;
}

void WriteFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write,
                         bool binary) {
  TemporaryOutput output(path);
  {
    std::ofstream out(output.temporary(), binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    if (!out) Fail(path.string(), "cannot open a temporary file for writing");
    write(out);
    out.flush();
    if (!out) Fail(path.string(), "write failed (disk full or I/O error)");
  }
  output.Commit();
}

void WriteFileAtomically(const fs::path& path, std::string_view bytes) {
  WriteFileAtomically(
      path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); },
      true);
}

std::string ReadWholeFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) Fail(path.string(), "file does not exist");
  if (fs::is_directory(path, ec)) Fail(path.string(), "is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path.string(), "cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) Fail(path.string(), "read error");
  return std::move(buffer).str();
}

}  // namespace contactlab
