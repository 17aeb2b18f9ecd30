// A triple buffer: one writer thread fills its back value and publishes it; one reader thread
// takes the newest published value. Neither waits on the other and neither allocates (the
// values are made, and sized, up front). Used by the live view's marks (contact_point_marks.h,
// scene/pair_contact_marks.h).
#pragma once

#include <array>
#include <atomic>

namespace contactlab {

template <class T>
class TripleBuffer {
 public:
  // Writer: the value being filled.
  T& back() { return values_[back_]; }
  // Writer: makes back() the newest published value and takes another to fill next.
  // Wait-free, allocation-free, never throws.
  void Publish() noexcept { back_ = middle_.exchange(back_ | kFresh, std::memory_order_acq_rel) & ~kFresh; }
  // Reader: the newest value published since the last call, or null when none was.
  const T* TakeNewest() noexcept {
    if (!(middle_.load(std::memory_order_acquire) & kFresh)) return nullptr;
    front_ = middle_.exchange(front_, std::memory_order_acq_rel) & ~kFresh;
    return &values_[front_];
  }
  // Before either thread runs: each of the three values, to size it.
  std::array<T, 3>& all() { return values_; }

 private:
  static constexpr int kFresh = 4;  // in middle_: the middle value is unread
  std::array<T, 3> values_;
  int back_ = 0;
  int front_ = 2;
  std::atomic<int> middle_{1};
};

}  // namespace contactlab
