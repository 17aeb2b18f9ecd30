#include "util/temporary_files.h"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace contactlab {
namespace {

constexpr int kMaxTemporaries = 64;
constexpr int kMaxPathBytes = 4096;

// A slot is free (0), being filled or emptied (1), or holds the path of a live temporary (2).
struct Slot {
  std::atomic<int> state{0};
  pid_t owner = 0;  // a forked child inherits the table but must not unlink its parent's files
  bool folder = false;  // a staging folder of files, emptied and removed
  char path[kMaxPathBytes];
};
Slot g_slots[kMaxTemporaries];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slot states");

// Unlinks the files in the folder PATH and removes it, with system calls only (no allocation):
// getdents64 into a buffer on the stack, read again from the start until nothing is left.
void EmptyAndRemoveFolder(const char* path) {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return;
  alignas(8) char buffer[4096];
  for (int pass = 0; pass < 64; ++pass) {
    bool removed = false;
    for (;;) {
      const ssize_t n = ::getdents64(fd, buffer, sizeof buffer);
      if (n <= 0) break;
      for (ssize_t at = 0; at < n;) {
        const auto* entry = reinterpret_cast<const dirent64*>(buffer + at);
        at += entry->d_reclen;
        const char* name = entry->d_name;
        if (name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0))) continue;
        if (::unlinkat(fd, name, 0) == 0) removed = true;
      }
    }
    if (!removed) break;
    ::lseek(fd, 0, SEEK_SET);
  }
  ::close(fd);
  ::rmdir(path);
}

int Register(const char* path, bool folder) {
  const std::size_t length = std::strlen(path);
  if (length >= kMaxPathBytes) return -1;
  for (int i = 0; i < kMaxTemporaries; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_slots[i].path, path, length + 1);
    g_slots[i].owner = ::getpid();
    g_slots[i].folder = folder;
    g_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void OnFatalSignal(int signal_number) {
  const int saved_errno = errno;
  UnlinkTemporaryFiles();
  errno = saved_errno;
  // SA_RESETHAND restored the default action; the re-raised signal arrives when we return.
  ::raise(signal_number);
}

}  // namespace

int RegisterTemporaryFile(const char* path) { return Register(path, false); }

int RegisterTemporaryFolder(const char* path) { return Register(path, true); }

void UnregisterTemporaryFile(int slot) {
  if (slot < 0 || slot >= kMaxTemporaries) return;
  g_slots[slot].state.store(0);
}

void UnlinkTemporaryFiles() {
  const pid_t self = ::getpid();
  // The files first: a file being written into a staging folder is unlinked before the folder.
  for (Slot& slot : g_slots) {
    if (slot.state.load() == 2 && slot.owner == self && !slot.folder) ::unlink(slot.path);
  }
  for (Slot& slot : g_slots) {
    if (slot.state.load() == 2 && slot.owner == self && slot.folder) EmptyAndRemoveFolder(slot.path);
  }
}

void InstallTemporaryFileCleanupOnSignals() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = OnFatalSignal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaction(signal_number, &sa, nullptr);
}

}  // namespace contactlab
