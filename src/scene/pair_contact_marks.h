// The contacts of every pair of a scene of many bodies, for the live view (docs/viewer.md): the
// haptic thread copies each touching pair's contacts (ContactModel::LatestContacts, world frame)
// into a frame sized at load, every few cycles, and hands the completed frame to a reader thread
// through a lock-free triple buffer (as ContactPointMarks does the points of one pointshell).
#pragma once

#include <cstdint>
#include <vector>

#include "contact/contact_model.h"
#include "haptics/triple_buffer.h"

namespace contactlab {

// One cycle's contacts over the pairs.
struct PairContactFrame {
  std::uint64_t sequence = 0;        // 1, 2, ... in the order frames completed; 0: none yet
  std::int64_t cycle = 0;            // the haptic cycle the contacts are of
  std::int32_t pairs_touching = 0;   // pairs whose model found contact
  std::int64_t not_kept = 0;         // contacts past the frame's room (or a model's), not listed
  std::vector<float> points;         // (3 #contacts) world frame, metres
  std::vector<float> normals;        // (3 #contacts) unit: the force on the pair's B
  std::vector<std::int32_t> pair;    // (#contacts) the contact's pair, an index of the scene's pairs
  int size() const { return int(pair.size()); }
};

class SceneWorld;

class PairContactMarks {
 public:
  // Frames of at most MAX_CONTACTS (> 0) contacts in all, taken every EVERY_CYCLES (> 0)
  // cycles. Throws Error for either out of range.
  PairContactMarks(int max_contacts, std::int64_t every_cycles);
  PairContactMarks(const PairContactMarks&) = delete;
  PairContactMarks& operator=(const PairContactMarks&) = delete;

  int max_contacts() const { return max_contacts_; }
  std::int64_t every_cycles() const { return every_; }

  // Haptic thread, at the end of WORLD's cycle CYCLE: on every EVERY_CYCLES-th cycle, copies the
  // touching pairs' contacts into the back frame and publishes it. Allocation-free (the models'
  // KeepContacts and this object's buffers were sized at load), lock-free, never throws.
  void Update(const SceneWorld& world, std::int64_t cycle) noexcept;

  // Reader (one thread at a time): swaps in the newest frame when one newer than *OUT's was
  // published and copies it to *OUT; false when there is none newer.
  bool TakeLatest(PairContactFrame* out);

 private:
  int max_contacts_;
  std::int64_t every_;
  TripleBuffer<PairContactFrame> frames_;
  std::uint64_t sequence_ = 0;
  ContactList scratch_;  // one pair's contacts, its room reserved
};

}  // namespace contactlab
