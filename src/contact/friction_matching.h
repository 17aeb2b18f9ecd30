// Friction anchors for contacts a model cannot index from cycle to cycle (contact/friction.h):
// a mesh-pair library reports new contacts each query (FCL's triangle-pair contacts, Bullet's
// manifold points of a one-off contactPairTest), so this matches them. Each contact of a query
// takes over the anchor of the previous query's contact nearest to it on A's surface (in A's
// frame) within `match_radius`. The anchor is shifted by the two contacts' offset on A, so the
// contact carries on with the displacement the previous one had, and keeps whether it slid. A
// contact with none within the radius starts a fresh anchor. Two contacts may take over the same
// one; a previous contact no one takes over is gone. The search is a spatial hash of the previous
// contacts with cells of the radius, so a query costs O(contacts) whatever their number.
// Everything is sized at load for CAPACITY contacts a query; past it a contact carries no friction
// (its normal force is untouched). Allocation-free and throws nothing after construction.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "contact/friction.h"
#include "geometry/pose.h"

namespace contactlab {

class MatchedFrictionAnchors {
 public:
  MatchedFrictionAnchors() = default;
  // Room for CAPACITY contacts a query, matched within RADIUS (metres, > 0). Allocates.
  MatchedFrictionAnchors(int capacity, double radius);

  // At the start of each query, A at X_BA in B's frame: the previous query's contacts become the
  // ones to match.
  void BeginQuery(const Pose& X_BA);
  // Forgets every anchor.
  void Reset() { current_ = 0, previous_ = 0; }

  // A contact of this query at P_A (A's frame), the same point P_B in B's frame, with unit normal
  // N_B, depth weight W and depth gradient G_B (B's frame; FrictionSums::Add): matched, its law
  // applied, its terms added to SUMS. Returns whether it slid, its displacement in *U; false and
  // a zero *U past the capacity.
  bool Add(const Eigen::Vector3d& p_A, const Eigen::Vector3d& p_B, const Eigen::Vector3d& n_B, double w,
           const Eigen::Vector3d& g_B, const FrictionParams& f, FrictionSums* sums, Eigen::Vector3d* u);

 private:
  struct Contact {
    Eigen::Vector3d p_A;       // where it is on A
    Eigen::Vector3d anchor_B;  // its anchor in B
    bool sliding = false;
  };
  std::int64_t CellKey(const Eigen::Vector3d& p_A, int dx, int dy, int dz) const;
  std::size_t Slot(std::int64_t key) const;
  int Nearest(const Eigen::Vector3d& p_A) const;  // index into previous contacts, -1: none within the radius

  std::vector<Contact> a_, b_;  // (capacity) this query's and the previous query's contacts, by turns
  bool a_is_current_ = true;
  int current_ = 0, previous_ = 0;  // how many of each
  double radius_ = 0;
  Pose X_BA_;
  // The spatial hash of the previous contacts: slot -> cell key, first contact, and the query
  // (stamp) it was filled in; each contact's next in its cell.
  std::vector<std::int64_t> slot_key_;
  std::vector<std::int32_t> slot_head_;
  std::vector<std::uint32_t> slot_stamp_;
  std::vector<std::int32_t> next_;
  std::uint32_t stamp_ = 0;
};

}  // namespace contactlab
