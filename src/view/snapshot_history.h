// The recent values of a stream, handed from one writer thread to any number of reader threads
// without locks: value k goes into slot k mod CAPACITY, each slot a sequence lock
// (latest_value.h). A reader asks for value k by its number and learns whether it is there,
// not published yet, or already overwritten by value k + CAPACITY. Used by live sessions so that
// every viewer's stream sends each snapshot once and in order, whenever its thread gets to run
// (live_view_server.h).
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "view/latest_value.h"

namespace contactlab {

enum class HistoryRead { kOk, kNotYet, kOverwritten };

template <class T, std::size_t kCapacity>
class SnapshotHistory {
  static_assert(kCapacity > 0);

 public:
  static constexpr std::size_t capacity() { return kCapacity; }

  // Writer (one thread): publishes VALUE as number published() (0, 1, ...). Wait-free,
  // allocation-free, never throws.
  void Publish(const T& value) noexcept {
    const std::uint64_t k = published_.load(std::memory_order_relaxed);
    slots_[k % kCapacity].Store(Entry{k, value});
    published_.store(k + 1, std::memory_order_release);
  }

  // Values published so far.
  std::uint64_t published() const noexcept { return published_.load(std::memory_order_acquire); }

  // Readers: copies value K to *OUT (kOk), or says it is not published yet or was overwritten
  // (the reader fell more than CAPACITY values behind).
  HistoryRead Get(std::uint64_t k, T* out) const noexcept {
    if (k >= published()) return HistoryRead::kNotYet;
    Entry e;
    if (!slots_[k % kCapacity].Load(&e)) return HistoryRead::kNotYet;
    if (e.index != k) return e.index > k ? HistoryRead::kOverwritten : HistoryRead::kNotYet;
    *out = e.value;
    return HistoryRead::kOk;
  }

  // Readers: the newest value; false before the first.
  bool Latest(T* out) const noexcept {
    for (;;) {
      const std::uint64_t n = published();
      if (n == 0) return false;
      if (Get(n - 1, out) == HistoryRead::kOk) return true;  // else overwritten meanwhile: a newer one is there
    }
  }

 private:
  struct Entry {
    std::uint64_t index;
    T value;
  };
  std::array<LatestValue<Entry>, kCapacity> slots_;
  std::atomic<std::uint64_t> published_{0};
};

}  // namespace contactlab
