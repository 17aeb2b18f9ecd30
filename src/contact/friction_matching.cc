#include "contact/friction_matching.h"

#include <algorithm>
#include <cmath>

namespace contactlab {

MatchedFrictionAnchors::MatchedFrictionAnchors(int capacity, double radius)
    : a_(std::size_t(std::max(0, capacity))), b_(std::size_t(std::max(0, capacity))), radius_(radius) {
  std::size_t slots = 16;
  while (slots < 2 * a_.size()) slots *= 2;
  slot_key_.assign(slots, 0);
  slot_head_.assign(slots, -1);
  slot_stamp_.assign(slots, 0u);
  next_.assign(a_.size(), -1);
}

std::int64_t MatchedFrictionAnchors::CellKey(const Eigen::Vector3d& p_A, int dx, int dy, int dz) const {
  // 21 bits a coordinate: cells of the radius over +-2^20 radii (a kilometre at 1 mm) wrap
  // beyond, which only makes far cells share a key (the distance test still decides).
  auto cell = [this](double x, int d) {
    const double c = std::floor(x / radius_);
    const std::int64_t i = std::isfinite(c) ? std::int64_t(std::clamp(c, -1e15, 1e15)) + d : 0;
    return i & ((std::int64_t(1) << 21) - 1);
  };
  return cell(p_A.x(), dx) | (cell(p_A.y(), dy) << 21) | (cell(p_A.z(), dz) << 42);
}

std::size_t MatchedFrictionAnchors::Slot(std::int64_t key) const {
  const std::uint64_t h = std::uint64_t(key) * 0x9E3779B97F4A7C15ull;
  return std::size_t(h >> 20) & (slot_key_.size() - 1);
}

void MatchedFrictionAnchors::BeginQuery(const Pose& X_BA) {
  X_BA_ = X_BA;
  a_is_current_ = !a_is_current_;
  previous_ = current_;
  current_ = 0;
  if (++stamp_ == 0) {  // the stamp wrapped: clear it
    std::fill(slot_stamp_.begin(), slot_stamp_.end(), 0u);
    stamp_ = 1;
  }
  const std::vector<Contact>& prev = a_is_current_ ? b_ : a_;
  const std::size_t mask = slot_key_.size() - 1;
  for (int j = 0; j < previous_; ++j) {
    const std::int64_t key = CellKey(prev[std::size_t(j)].p_A, 0, 0, 0);
    std::size_t s = Slot(key);
    while (slot_stamp_[s] == stamp_ && slot_key_[s] != key) s = (s + 1) & mask;  // at most half full
    if (slot_stamp_[s] != stamp_) {
      slot_stamp_[s] = stamp_;
      slot_key_[s] = key;
      slot_head_[s] = -1;
    }
    next_[std::size_t(j)] = slot_head_[s];
    slot_head_[s] = j;
  }
}

int MatchedFrictionAnchors::Nearest(const Eigen::Vector3d& p_A) const {
  const std::vector<Contact>& prev = a_is_current_ ? b_ : a_;
  const std::size_t mask = slot_key_.size() - 1;
  int best = -1;
  double best_d2 = radius_ * radius_;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const std::int64_t key = CellKey(p_A, dx, dy, dz);
        std::size_t s = Slot(key);
        while (slot_stamp_[s] == stamp_ && slot_key_[s] != key) s = (s + 1) & mask;
        if (slot_stamp_[s] != stamp_) continue;
        for (int j = slot_head_[s]; j >= 0; j = next_[std::size_t(j)]) {
          const double d2 = (prev[std::size_t(j)].p_A - p_A).squaredNorm();
          if (d2 <= best_d2) best_d2 = d2, best = j;
        }
      }
  return best;
}

bool MatchedFrictionAnchors::Add(const Eigen::Vector3d& p_A, const Eigen::Vector3d& p_B, const Eigen::Vector3d& n_B,
                                 double w, const Eigen::Vector3d& g_B, const FrictionParams& f, FrictionSums* sums,
                                 Eigen::Vector3d* u) {
  if (current_ >= int(a_.size())) {
    u->setZero();
    return false;
  }
  const std::vector<Contact>& prev = a_is_current_ ? b_ : a_;
  Contact c{p_A, p_B, false};
  bool slid_before = false;
  if (const int j = Nearest(p_A); j >= 0) {
    const Contact& p = prev[std::size_t(j)];
    c.anchor_B = p.anchor_B + (p_B - X_BA_ * p.p_A);  // its displacement, carried over
    slid_before = p.sliding;
  }
  *u = ApplyCoulomb(p_B, n_B, f, slid_before, &c.anchor_B, &c.sliding);
  sums->Add(p_B, n_B, w, g_B, c.anchor_B, *u, c.sliding, f);
  (a_is_current_ ? a_ : b_)[std::size_t(current_++)] = c;
  return c.sliding;
}

}  // namespace contactlab
