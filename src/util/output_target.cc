#include "util/output_target.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

#include "util/error.h"
#include "util/input_files.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

// What a non-regular file is, in a few words.
const char* KindOf(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory: return "a folder";
    case fs::file_type::character:
    case fs::file_type::block: return "a device";
    case fs::file_type::fifo: return "a named pipe";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

// FOLDER, or the nearest folder above it that exists (the current folder for a relative path
// that has none).
fs::path NearestExistingFolder(const fs::path& folder) {
  std::error_code ec;
  fs::path p = folder.empty() ? fs::path(".") : folder;
  while (!fs::exists(p, ec) && p.has_relative_path() && p.has_parent_path() && p != p.parent_path()) {
    p = p.parent_path();
  }
  if (!fs::exists(p, ec)) return ".";
  return p;
}

// Creates and removes a probe file in FOLDER (an existing path); throws Error naming OUTPUT and
// WHAT when it cannot.
void ProbeWritableFolder(const fs::path& folder, const fs::path& output, std::string_view what) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    Fail(output.string(), std::string(what) + ": " + folder.string() + " is not a folder");
  }
  static std::atomic<unsigned> counter{0};
  const fs::path probe = folder / (".contactlab-probe-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    Fail(output.string(), std::string(what) + ": cannot write in " + folder.string() + ": " + std::strerror(err) +
                              " (checked before the work)");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace

void CheckOutputWritable(const fs::path& path, std::string_view what) {
  CheckOutputTarget(path, what);
  CheckOutputIsNoRecordedInput(path, what);
  ProbeWritableFolder(NearestExistingFolder(path.parent_path()), path, what);
}

void CheckOutputFolderWritable(const fs::path& folder, std::string_view what) {
  CheckOutputFolder(folder, what);
  std::error_code ec;
  const fs::path absolute = fs::absolute(folder, ec).lexically_normal();
  const fs::path named = absolute.has_filename() ? absolute : absolute.parent_path();
  ProbeWritableFolder(NearestExistingFolder(named.parent_path()), folder, what);
  if (fs::is_directory(named, ec)) ProbeWritableFolder(named, folder, what);
}

void CheckOutputTarget(const fs::path& path, std::string_view what) {
  if (path.empty()) Fail(what, "the output path is empty");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found || status.type() == fs::file_type::regular) return;
  if (ec) Fail(path.string(), std::string(what) + ": cannot inspect the output: " + ec.message());
  Fail(path.string(), std::string(what) + " is " + KindOf(status.type()) + ", not a regular file; refusing to replace it");
}

void CheckOutputFolder(const fs::path& path, std::string_view what) {
  if (path.empty()) Fail(what, "the output folder is empty");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found && fs::is_symlink(fs::symlink_status(path, ec))) {
    // A link to nothing: committing the results would replace the link by the new folder.
    Fail(path.string(), std::string(what) + " is a symlink to " + fs::read_symlink(path, ec).string() +
                            ", which does not exist: create that folder, or name a folder that is no link");
  }
  if (status.type() == fs::file_type::not_found || status.type() == fs::file_type::directory) return;
  if (ec) Fail(path.string(), std::string(what) + ": cannot inspect the output folder: " + ec.message());
  const std::string kind = status.type() == fs::file_type::regular ? "a file" : KindOf(status.type());
  Fail(path.string(), std::string(what) + " is " + kind + ", not a folder");
}

void CheckOutputIsNotInput(const fs::path& output, const fs::path& input, std::string_view what) {
  std::error_code ec;
  bool same = fs::exists(output, ec) && fs::exists(input, ec) && fs::equivalent(output, input, ec);
  if (!same) {
    const fs::path a = fs::weakly_canonical(fs::absolute(output, ec), ec);
    const fs::path b = fs::weakly_canonical(fs::absolute(input, ec), ec);
    same = !a.empty() && a == b;
  }
  if (same) Fail(output.string(), std::string(what) + " is the input " + input.string() + "; refusing to overwrite it");
}

}  // namespace contactlab
