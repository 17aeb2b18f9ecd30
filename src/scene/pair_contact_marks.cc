// The contacts of every pair of a scene of many bodies, copied by the haptic thread.
#include "scene/pair_contact_marks.h"

#include <algorithm>
#include <string>

#include "scene/scene_world.h"
#include "util/error.h"

namespace contactlab {

PairContactMarks::PairContactMarks(int max_contacts, std::int64_t every_cycles)
    : max_contacts_(max_contacts), every_(every_cycles) {
  if (max_contacts_ <= 0) Fail("pair contact marks", "room for " + std::to_string(max_contacts_) + " contacts");
  if (every_ <= 0) Fail("pair contact marks", "frames must be at least 1 cycle apart");
  for (PairContactFrame& f : frames_.all()) {
    f.points.reserve(3 * std::size_t(max_contacts_));
    f.normals.reserve(3 * std::size_t(max_contacts_));
    f.pair.reserve(std::size_t(max_contacts_));
  }
  scratch_.points.reserve(std::size_t(max_contacts_));
  scratch_.normals.reserve(std::size_t(max_contacts_));
  scratch_.depths.reserve(std::size_t(max_contacts_));
  scratch_.areas.reserve(std::size_t(max_contacts_));
  scratch_.pressures.reserve(std::size_t(max_contacts_));
}

void PairContactMarks::Update(const SceneWorld& world, std::int64_t cycle) noexcept {
  if (cycle % every_ != 0) return;
  PairContactFrame& f = frames_.back();
  f.cycle = cycle;
  f.pairs_touching = 0;
  f.not_kept = 0;
  f.points.clear(), f.normals.clear(), f.pair.clear();
  for (const int p : world.near_pairs()) {
    const PairOutcome& o = world.outcome(p);
    if (o.result.stats.points_in_contact <= 0) continue;
    ++f.pairs_touching;
    world.model_const(p).LatestContacts(&scratch_);
    const int room = max_contacts_ - f.size();
    const int n = std::min(scratch_.size(), room);
    f.not_kept += scratch_.not_kept + (scratch_.size() - n);
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        f.points.push_back(float(scratch_.points[std::size_t(i)][c]));
        f.normals.push_back(float(scratch_.normals[std::size_t(i)][c]));
      }
      f.pair.push_back(p);
    }
  }
  f.sequence = ++sequence_;
  frames_.Publish();
}

bool PairContactMarks::TakeLatest(PairContactFrame* out) {
  const PairContactFrame* newest = frames_.TakeNewest();
  if (newest == nullptr || newest->sequence <= out->sequence) return false;
  const PairContactFrame& f = *newest;
  out->sequence = f.sequence;
  out->cycle = f.cycle;
  out->pairs_touching = f.pairs_touching;
  out->not_kept = f.not_kept;
  out->points.assign(f.points.begin(), f.points.end());
  out->normals.assign(f.normals.begin(), f.normals.end());
  out->pair.assign(f.pair.begin(), f.pair.end());
  return true;
}

}  // namespace contactlab
