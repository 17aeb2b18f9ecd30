// Per-point contact state of the displayed pointshell points for the live view (Barbič & James
// 2008, Fig. 2: points in contact, points traversed): the haptic thread marks a chunk of the
// points after each contact query and, when every point is marked, hands the completed sweep to
// a reader thread through a lock-free triple buffer. A sweep thus spans a few consecutive cycles.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "contact/contact_model.h"
#include "haptics/triple_buffer.h"

namespace contactlab {

// One complete pass over the displayed points.
struct PointMarkSweep {
  std::uint64_t sequence = 0;       // 1, 2, ... in the order sweeps completed; 0: none yet
  std::int64_t first_cycle = 0;     // haptic cycles whose queries the marks come from
  std::int64_t last_cycle = 0;
  std::int32_t in_contact = 0;      // points marked kInContact
  std::int32_t evaluated = 0;       // points marked kClear or kInContact
  std::vector<PointState> states;   // (#points) in the order of the constructor's POINTS
};

class ContactPointMarks {
 public:
  static constexpr int kDefaultChunk = 2048;

  // POINTS: indices into body A's pointshell of the points to mark (the displayed ones), at
  // most CHUNK (> 0) of them marked per cycle. Throws Error for an empty POINTS or CHUNK <= 0.
  explicit ContactPointMarks(std::vector<std::int32_t> points, int chunk = kDefaultChunk);
  ContactPointMarks(const ContactPointMarks&) = delete;
  ContactPointMarks& operator=(const ContactPointMarks&) = delete;

  int size() const { return int(points_.size()); }

  // Haptic thread, right after MODEL.Evaluate(QUERY) of cycle CYCLE: marks the next chunk
  // (ContactModel::PointStates) and publishes the sweep it completes. A model without
  // pointshell states (PointStates returns 0) turns the marks off for good. Allocation-free,
  // lock-free, never throws.
  void Update(ContactModel& model, const ContactQuery& query, std::int64_t cycle) noexcept;

  // False once a model answered that it has no pointshell states.
  bool supported() const { return supported_.load(std::memory_order_relaxed); }

  // Reader (one thread at a time): swaps in the newest completed sweep when one newer than
  // *OUT's was published and copies it to *OUT (allocating only when *OUT is smaller); false
  // when there is none newer.
  bool TakeLatest(PointMarkSweep* out);

 private:
  std::vector<std::int32_t> points_;
  int chunk_;
  TripleBuffer<PointMarkSweep> sweeps_;
  std::atomic<bool> supported_{true};
  int cursor_ = 0;                  // next point of the sweep being marked
  std::uint64_t sequence_ = 0;
};

}  // namespace contactlab
