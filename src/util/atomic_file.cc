#include "util/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <string>

#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;

void WriteFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write,
                         bool binary) {
  // Unique per process and per call, so threads writing the same target never collide.
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  std::error_code ec;
  if (path.has_parent_path() && !fs::exists(path.parent_path(), ec)) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) Fail(path.string(), "cannot create the output folder: " + ec.message());
  }
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
      if (!out) Fail(path.string(), "cannot open a temporary file for writing");
      write(out);
      out.flush();
      if (!out) Fail(path.string(), "write failed (disk full or I/O error)");
    }
    fs::rename(tmp, path, ec);
    if (ec) Fail(path.string(), "cannot rename the finished temporary file: " + ec.message());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
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
