#include "util/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "util/error.h"
#include "util/input_files.h"
#include "util/number_text.h"
#include "util/output_target.h"
#include "util/temporary_files.h"

namespace contactlab {
namespace fs = std::filesystem;

TemporaryOutput::TemporaryOutput(fs::path path) : path_(std::move(path)) {
  CheckOutputTarget(path_, "the output");
  CheckOutputIsNoRecordedInput(path_, "the output");
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
  // The target may have been replaced by something else, or read as an input, while we wrote.
  CheckOutputTarget(path_, "the output");
  CheckOutputIsNoRecordedInput(path_, "the output");
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
    try {
      write(out);
    } catch (const NonFiniteValue& e) {
      Fail(path.string(), e.what());  // the temporary is removed with OUTPUT
    }
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

namespace {

std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISREG(mode)) return "";
  return "not a regular file";
}

}  // namespace

std::string NonRegularFileKind(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "";
  return KindOf(st.st_mode);
}

void CheckInputFile(const fs::path& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) Fail(path.string(), std::string(what) + " not found");
    Fail(path.string(), "cannot read: " + std::string(std::strerror(err)));
  }
  const std::string kind = KindOf(st.st_mode);
  if (!kind.empty()) Fail(path.string(), "is " + kind + ", not a " + std::string(what));
}

std::string ReadWholeFile(const fs::path& path) {
  // Opened without blocking (a named pipe with no writer would wait forever) and checked on
  // the open descriptor, so what is read is the regular file that was checked.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) Fail(path.string(), "file does not exist");
    CheckInputFile(path);  // names a folder or special file when that is why
    Fail(path.string(), "cannot open for reading: " + std::string(std::strerror(err)));
  }
  struct stat st {};
  const bool stated = ::fstat(fd, &st) == 0;
  if (!stated || !S_ISREG(st.st_mode)) {
    const std::string kind = stated ? KindOf(st.st_mode) : "unreadable";
    ::close(fd);
    Fail(path.string(), "is " + kind + ", not a file");
  }
  std::string bytes;
  if (st.st_size > 0) bytes.reserve(std::size_t(st.st_size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      Fail(path.string(), "read error: " + std::string(std::strerror(err)));
    }
    if (n == 0) break;
    bytes.append(buffer, std::size_t(n));
  }
  ::close(fd);
  RecordInputFile(path);
  return bytes;
}

}  // namespace contactlab
