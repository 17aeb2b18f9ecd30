// Per-point contact state of the displayed pointshell points, marked by the haptic thread.
#include "haptics/contact_point_marks.h"

#include <algorithm>
#include <span>

#include "util/error.h"

namespace contactlab {

ContactPointMarks::ContactPointMarks(std::vector<std::int32_t> points, int chunk)
    : points_(std::move(points)), chunk_(chunk) {
  if (points_.empty()) Fail("contact point marks", "no points to mark");
  if (chunk_ <= 0) Fail("contact point marks", "the chunk must be positive, got " + std::to_string(chunk_));
  for (PointMarkSweep& b : sweeps_.all()) b.states.assign(points_.size(), PointState::kNotEvaluated);
}

void ContactPointMarks::Update(ContactModel& model, const ContactQuery& query, std::int64_t cycle) noexcept {
  if (!supported_.load(std::memory_order_relaxed)) return;
  PointMarkSweep& sweep = sweeps_.back();
  if (cursor_ == 0) {
    sweep.first_cycle = cycle;
    sweep.in_contact = sweep.evaluated = 0;
  }
  const int n = std::min(chunk_, size() - cursor_);
  PointState* out = sweep.states.data() + cursor_;
  const int written = model.PointStates(query, std::span<const std::int32_t>(points_.data() + cursor_, std::size_t(n)), out);
  if (written <= 0) {
    supported_.store(false, std::memory_order_relaxed);
    return;
  }
  for (int k = 0; k < written; ++k) {
    sweep.in_contact += out[k] == PointState::kInContact;
    sweep.evaluated += out[k] != PointState::kNotEvaluated;
  }
  cursor_ += written;
  sweep.last_cycle = cycle;
  if (cursor_ < size()) return;
  // Complete: publish it as the middle buffer and take the old middle to write the next.
  cursor_ = 0;
  sweep.sequence = ++sequence_;
  sweeps_.Publish();
}

bool ContactPointMarks::TakeLatest(PointMarkSweep* out) {
  const PointMarkSweep* newest = sweeps_.TakeNewest();
  if (newest == nullptr || newest->sequence <= out->sequence) return false;
  const PointMarkSweep& sweep = *newest;
  out->sequence = sweep.sequence;
  out->first_cycle = sweep.first_cycle;
  out->last_cycle = sweep.last_cycle;
  out->in_contact = sweep.in_contact;
  out->evaluated = sweep.evaluated;
  out->states.assign(sweep.states.begin(), sweep.states.end());
  return true;
}

}  // namespace contactlab
