// The latest of a stream of values, handed from one writer thread to any number of reader
// threads without locks (a sequence lock): the writer never waits, a reader retries while a
// write is under way. Used by live sessions to pass the newest haptic cycle record to the
// viewer's HTTP thread (live_view_server.h).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace contactlab {

template <class T>
class LatestValue {
  static_assert(std::is_trivially_copyable_v<T>, "values are copied as bytes");
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;

 public:
  // Writer (one thread): makes VALUE the latest. Wait-free, allocation-free, never throws.
  void Store(const T& value) noexcept {
    std::uint64_t w[kWords] = {};
    std::memcpy(w, &value, sizeof(T));
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);  // odd: a write is under way
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i) words_[i].store(w[i], std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }

  // Readers: copies the latest value to *OUT; false when nothing was stored yet.
  bool Load(T* out) const noexcept {
    for (;;) {
      const std::uint64_t s0 = seq_.load(std::memory_order_acquire);
      if (s0 == 0) return false;
      if (s0 & 1) continue;
      std::uint64_t w[kWords];
      for (std::size_t i = 0; i < kWords; ++i) w[i] = words_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s0) {
        std::memcpy(out, w, sizeof(T));
        return true;
      }
    }
  }

  // Values stored so far.
  std::uint64_t version() const noexcept { return seq_.load(std::memory_order_acquire) / 2; }

 private:
  std::atomic<std::uint64_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace contactlab
