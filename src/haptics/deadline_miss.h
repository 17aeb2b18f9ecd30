// Deadline misses of the 1 kHz haptic loop with a cause (Barbič & James 2008, sec. 5: one
// haptic cycle per millisecond): what a missed cycle did, whether the work itself overran the
// period or the thread was not running, and the largest misses of a session kept in a fixed
// array so that the loop records them without allocating.
#pragma once

#include <array>
#include <cstdint>

namespace contactlab {

// Why a cycle missed its deadline. The rule (ClassifyMiss): a missed cycle is an *overrun*
// when the loop thread's CPU time over the cycle's work exceeds the period, i.e. the cycle
// would have missed even had the thread run without interruption from its release; otherwise
// it is *preempted*: the work fit in the period and the deadline passed while the thread was
// not running (woken late, preempted, or an interrupt or the hypervisor held its core).
enum class MissCause : std::uint8_t { kOverrun, kPreempted };

// The cause of a missed cycle whose work took CPU_NS of the loop thread's CPU time, at a
// period of PERIOD_NS.
constexpr MissCause ClassifyMiss(std::int64_t cpu_ns, std::int64_t period_ns) {
  return cpu_ns > period_ns ? MissCause::kOverrun : MissCause::kPreempted;
}

constexpr const char* MissCauseName(MissCause cause) {
  return cause == MissCause::kOverrun ? "overrun" : "preempted";
}

// One missed cycle: its times and what it did. Trivially copyable.
struct MissRecord {
  std::int64_t cycle = 0;          // the haptic cycle's number (CycleRecord::cycle)
  std::int64_t at_ns = 0;          // start of its work after the loop's start, ns
  std::int64_t wall_ns = 0;        // wall time from its release to the wrench written, ns
  std::int64_t wake_ns = 0;        // of which the wake-up's lateness after the release, ns
  std::int64_t work_ns = 0;        // wall time of the work (read, contact, coupling, write), ns
  std::int64_t cpu_ns = 0;         // the loop thread's CPU time over the work, ns
  std::int64_t nodes_visited = 0;  // what the cycle did: contact tree nodes visited,
  std::int32_t points_in_contact = 0;  // points in contact,
  std::int32_t level_rendered = -1;    // deepest level rendered,
  std::int64_t step_ns = 0;            // and the deformation steps within the work, ns
  MissCause cause = MissCause::kPreempted;
};

// The kCapacity largest misses by wall time, largest first; a miss equal to the smallest kept
// one does not displace it (the earlier one stays). Offer is allocation-free, lock-free and
// never throws: the haptic loop calls it from its cycle.
class LargestMisses {
 public:
  static constexpr int kCapacity = 10;

  // Keeps MISS when fewer than kCapacity are kept or it is larger than the smallest kept.
  void Offer(const MissRecord& miss) noexcept {
    if (size_ == kCapacity && !(miss.wall_ns > misses_[kCapacity - 1].wall_ns)) return;
    // Insertion into the sorted array: shift the smaller ones down by one (the last falls off).
    int i = size_ < kCapacity ? size_++ : kCapacity - 1;
    while (i > 0 && misses_[i - 1].wall_ns < miss.wall_ns) {
      misses_[i] = misses_[i - 1];
      --i;
    }
    misses_[i] = miss;
  }

  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // The I-th largest, 0 <= I < size().
  const MissRecord& operator[](int i) const { return misses_[i]; }
  const MissRecord* begin() const { return misses_.data(); }
  const MissRecord* end() const { return misses_.data() + size_; }

 private:
  std::array<MissRecord, kCapacity> misses_{};  // [0, size_) sorted by wall_ns, descending
  int size_ = 0;
};

}  // namespace contactlab
