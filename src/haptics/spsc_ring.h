// A fixed-capacity lock-free single-producer single-consumer ring buffer: the haptic loop
// (producer, 1 kHz, Barbič & James 2008 sec. 5) hands cycle records to a graphics or logging
// consumer without locks or allocation.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>

namespace contactlab {

// Ring of CAPACITY slots (a power of two) of trivially copyable T. Exactly one thread may call
// TryPush and exactly one (other) thread TryPop/Drop; both are wait-free, allocation-free and
// never throw. Indices are free-running 64-bit counters: head_ (next to read) is written only
// by the consumer, tail_ (next to write) only by the producer.
template <typename T, std::size_t Capacity>
class SpscRing {
  static_assert(Capacity >= 2 && (Capacity & (Capacity - 1)) == 0, "capacity must be a power of two");
  static_assert(std::is_trivially_copyable_v<T>, "ring elements are copied by value");

 public:
  static constexpr std::size_t kCapacity = Capacity;

  // Producer: copies VALUE in; returns false (and counts a drop) when the ring is full.
  bool TryPush(const T& value) noexcept {
    const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
    if (tail - head_cache_ >= Capacity) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail - head_cache_ >= Capacity) {
        dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
        return false;
      }
    }
    slots_[tail & (Capacity - 1)] = value;
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Consumer: copies the oldest element to *OUT; returns false when the ring is empty.
  bool TryPop(T* out) noexcept {
    const std::uint64_t head = head_.load(std::memory_order_relaxed);
    if (head == tail_cache_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head == tail_cache_) return false;
    }
    *out = slots_[head & (Capacity - 1)];
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Approximate number of queued elements (exact when called by either side while the other
  // is idle).
  std::size_t SizeApprox() const noexcept {
    return std::size_t(tail_.load(std::memory_order_acquire) - head_.load(std::memory_order_acquire));
  }
  // Elements the producer could not push because the ring was full.
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  static constexpr std::size_t kLine = 64;  // keep the two sides' indices on separate cache lines
  alignas(kLine) std::atomic<std::uint64_t> head_{0};
  std::uint64_t tail_cache_ = 0;            // consumer's copy of tail_
  alignas(kLine) std::atomic<std::uint64_t> tail_{0};
  std::uint64_t head_cache_ = 0;            // producer's copy of head_
  std::atomic<std::uint64_t> dropped_{0};
  alignas(kLine) std::array<T, Capacity> slots_{};
};

}  // namespace contactlab
