#include "util/temporary_files.h"

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
  char path[kMaxPathBytes];
};
Slot g_slots[kMaxTemporaries];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slot states");

void OnFatalSignal(int signal_number) {
  const int saved_errno = errno;
  UnlinkTemporaryFiles();
  errno = saved_errno;
  // SA_RESETHAND restored the default action; the re-raised signal arrives when we return.
  ::raise(signal_number);
}

}  // namespace

int RegisterTemporaryFile(const char* path) {
  const std::size_t length = std::strlen(path);
  if (length >= kMaxPathBytes) return -1;
  for (int i = 0; i < kMaxTemporaries; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_slots[i].path, path, length + 1);
    g_slots[i].owner = ::getpid();
    g_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void UnregisterTemporaryFile(int slot) {
  if (slot < 0 || slot >= kMaxTemporaries) return;
  g_slots[slot].state.store(0);
}

void UnlinkTemporaryFiles() {
  const pid_t self = ::getpid();
  for (Slot& slot : g_slots) {
    if (slot.state.load() == 2 && slot.owner == self) ::unlink(slot.path);
  }
}

void InstallTemporaryFileCleanupOnSignals() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = OnFatalSignal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

}  // namespace contactlab
