#include "util/atomic_folder.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <utility>

#include "util/error.h"
#include "util/input_files.h"
#include "util/output_target.h"
#include "util/temporary_files.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

std::string ErrnoText() { return std::strerror(errno); }

// Whether renameat2 failed because the file system lacks the flag (NFS, some FUSE ones).
bool Unsupported(int err) { return err == EINVAL || err == ENOSYS || err == EOPNOTSUPP; }

// The names in FOLDER (empty when it does not exist).
std::vector<std::string> EntriesOf(const fs::path& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    names.push_back(it->path().filename().string());
  }
  return names;
}

}  // namespace

TemporaryFolder::TemporaryFolder(fs::path path, std::function<bool(const std::string&)> keep)
    : keep_(std::move(keep)) {
  CheckOutputFolder(path, "the output folder");
  std::error_code ec;
  path_ = fs::absolute(path, ec).lexically_normal();
  if (!path_.has_filename()) path_ = path_.parent_path();  // a trailing slash
  if (fs::is_symlink(fs::symlink_status(path_, ec)) && fs::is_directory(path_, ec)) {
    path_ = fs::canonical(path_, ec);  // a link to a folder is followed (CheckOutputFolder refused one to nothing)
    if (ec) Fail(path.string(), "cannot follow the symlink: " + ec.message());
  }
  if (path_.empty() || path_ == path_.root_path()) Fail(path.string(), "cannot be a results folder");
  fs::create_directories(path_.parent_path(), ec);
  if (ec) Fail(path_.string(), "cannot create the folder it goes in: " + ec.message());
  static std::atomic<unsigned> counter{0};
  temporary_ = path_.string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  if (!fs::create_directory(temporary_, ec) || ec) {
    Fail(path_.string(), "cannot create the staging folder " + temporary_.string() + ": " +
                             (ec ? ec.message() : std::string("it exists")));
  }
  slot_ = RegisterTemporaryFolder(temporary_.c_str());
}

TemporaryFolder::~TemporaryFolder() {
  if (!committed_) MoveKeptEntriesBack();
  std::error_code ec;
  fs::remove_all(temporary_, ec);  // the unfinished new folder, or after Commit the old one
  UnregisterTemporaryFile(slot_);
}

void TemporaryFolder::Write(const std::string& name, std::string_view bytes) {
  const fs::path target = path_ / name;
  const int fd = ::open((temporary_ / name).c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) Fail(target.string(), "cannot create it in the staging folder: " + ErrnoText());
  written_.push_back(name);
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = ErrnoText();
      ::close(fd);
      Fail(target.string(), "write failed (" + why + "); the folder is left as it was");
    }
    done += std::size_t(n);
  }
  if (::close(fd) != 0) Fail(target.string(), "write failed (" + ErrnoText() + "); the folder is left as it was");
}

void TemporaryFolder::MoveKeptEntries() {
  for (const std::string& name : EntriesOf(path_)) {
    const bool replaced = std::find(written_.begin(), written_.end(), name) != written_.end();
    if (!replaced && keep_(name)) {
      if (::rename((path_ / name).c_str(), (temporary_ / name).c_str()) != 0) {
        Fail((path_ / name).string(), "cannot move it into the new folder: " + ErrnoText());
      }
      moved_.push_back(name);
    } else {
      CheckOutputIsNoRecordedInput(path_ / name, "the output");
    }
  }
}

void TemporaryFolder::MoveKeptEntriesBack() {
  for (const std::string& name : moved_) ::rename((temporary_ / name).c_str(), (path_ / name).c_str());
  moved_.clear();
}

void TemporaryFolder::Commit() {
  if (committed_) return;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path_, ec))) {
    if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, path_.c_str(), RENAME_NOREPLACE) != 0 &&
        (!Unsupported(errno) || ::rename(temporary_.c_str(), path_.c_str()) != 0)) {
      Fail(path_.string(), "cannot rename the finished staging folder onto it: " + ErrnoText());
    }
    UnregisterTemporaryFile(slot_);
    slot_ = -1;
    committed_ = true;
    return;
  }
  CheckOutputFolder(path_, "the output folder");
  // From here the staging folder may hold old entries: a signal must leave it, not empty it.
  UnregisterTemporaryFile(slot_);
  slot_ = -1;
  MoveKeptEntries();
  if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, path_.c_str(), RENAME_EXCHANGE) == 0) {
    committed_ = true;  // the staging name now holds the old folder, removed by the destructor
    return;
  }
  const int err = errno;
  // Without the exchange: the old folder renamed aside, the new one onto its name (in between a
  // reader finds no folder, never a mixture), the old one removed by the destructor.
  const fs::path aside = temporary_.string() + "-old";
  if (Unsupported(err) && ::rename(path_.c_str(), aside.c_str()) == 0) {
    if (::rename(temporary_.c_str(), path_.c_str()) == 0) {
      temporary_ = aside;
      committed_ = true;
      return;
    }
    ::rename(aside.c_str(), path_.c_str());
  }
  const std::string why = std::strerror(Unsupported(err) ? errno : err);
  MoveKeptEntriesBack();
  Fail(path_.string(), "cannot exchange the old folder for the new one: " + why);
}

}  // namespace contactlab
