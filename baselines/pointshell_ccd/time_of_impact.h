// Continuous collision of a pointshell against a distance field (after Xu & Barbič, "6-DoF
// Haptic Rendering Using Continuous Collision Detection between Points and Signed Distance
// Fields", IEEE Trans. Haptics 2017): the earliest time at which any point of body A's
// pointshell reaches a level of body B's field while B moves, and the points near B's surface
// at one pose (the constraints of the proxy's sliding step).
//
// The motion. B moves in A's frame from pose X0 = (R0, o0) by the twist (v, w):
//     R(t) = exp(t [w]) R0,   o(t) = o0 + t v,   t in [0, 1],
// its origin on a straight line and its rotation at a constant rate about a fixed axis through
// its origin (a linear blend, not a screw). The haptic device reports where the handle is, and
// the handle's point — B's origin — travels in a straight line between two samples; the blend
// also keeps the travel bound simple: a point p of A sits at q(t) = R(t)^T (p - o(t)) in B's
// frame and moves no faster than
//     |dq/dt| <= |w| max(|p - o0|, |p - o0 - v|) + |v|,
// because |p - o(t)| is convex in t. A screw would move the origin on a helix, which a
// straight-line sample of the device does not suggest.
//
// The search. Conservative advancement (Mirtich 1996) on the pointshell tree, breadth first:
// a node (its point c, bounding radius r, speed bound s of its subtree) cannot reach the level
// before d(q_c(t)) - λ r - level > 0 says so, and advancing t by that margin over λ s is safe
// (λ: the field's Lipschitz bound). A node's advanced time is where its children start, and a
// node whose time passes the earliest impact found so far is culled. A point advances the same
// way, in steps of at least max(ε, level) / (λ s), so a dip below the level that does not reach
// the field's zero (or ε below a level under ε) may go unseen, and a sign change brackets the
// impact, which regula falsi (Illinois) refines on the trilinear field. A point already below
// the level at t = 0 (in contact) takes min(level, d(0) - ε) as its own level: it may slide but
// not sink further by more than 2ε.
//
// What a search looks up. A node's first child is its own point one level down, and starts
// where the parent stopped advancing: when that was at a lookup, the child takes its distance
// rather than looking it up again. A motion that starts where the latest Near ran takes the
// distances Near looked up there for every node that starts at t = 0 (Near, below). Each level
// advances four nodes or points at a time, a step of each in turn (one node's steps depend on
// each other, different nodes' do not). Above the last level the earliest impact does not move,
// so each node advances exactly as alone; on the last, each point sees the earliest impact found
// so far when it steps, so which points are in flight together can move a point's steps that
// are cut at that time, and with them, within the dips above, the impact found (by about 1e-6
// of the step in the tunnelling and slide runs).
//
// Graceful degradation: the budget counts the nodes visited and the lookups of the nodes and
// points stepping along the motion, one each. Past it the remaining nodes are not expanded and
// the nodes and points in flight take no further step; each stops the motion at its own
// conservative time (a bound, never later than any of its points), so a small budget makes the
// proxy stop early, never pass through.
//
// Allocation-free and exception-free after construction.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/pose.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

// B's pose in A's frame along one motion (see above).
struct BlendMotion {
  Eigen::Quaterniond R0 = Eigen::Quaterniond::Identity();
  Eigen::Vector3d o0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  // translation of B's origin over the motion
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  // rotation vector applied over the motion

  // The motion from X0 to X1 (poses of B in A; unit quaternions), the shorter way round.
  static BlendMotion Between(const Pose& X0, const Pose& X1);
  // The motion from X0 by the twist (V, W).
  static BlendMotion From(const Pose& X0, const Eigen::Vector3d& V, const Eigen::Vector3d& W) {
    return {X0.rotation, X0.translation, V, W};
  }
  Pose At(double t) const;
};

struct ImpactParams {
  double level = 0;       // metres: a point touches when its distance to B reaches it
  double slack = 0;       // ε, metres, < level: see above (the dips that may go unseen)
  double lipschitz = 1;   // λ >= 1, bound on |∇d|
  std::int64_t node_budget = 0;  // nodes visited plus steps taken, at most; <= 0: no limit
};

struct ImpactResult {
  double t = 1;           // earliest impact in [0, 1]; 1 when nothing reaches the level
  bool hit = false;
  std::int32_t point = -1;      // the point that reaches it (-1: none, or a node cut by the budget)
  std::int64_t nodes_visited = 0;
  std::int64_t steps = 0;  // lookups of nodes and points stepping along the motion
  bool degraded = false;  // the budget cut the traversal
};

// A point of A near B's surface at a pose: the constraint of the proxy's sliding step.
struct NearPoint {
  std::int32_t point = -1;       // index in the pointshell
  double distance = 0;           // d at the pose, metres (a node's lower bound when degraded)
  Eigen::Vector3d p_A;           // position in A's frame
  Eigen::Vector3d gradient_A;    // ∇d in A's frame (unit length where the field is exact)
};

class ImpactSearch {
 public:
  // SHELL is A's pointshell (A's frame), FIELD is B's field (B's frame); both must outlive it.
  ImpactSearch(std::shared_ptr<const Pointshell> shell, std::shared_ptr<const DistanceField> field);

  const Pointshell& shell() const { return *shell_; }
  const DistanceField& field() const { return *field_; }

  // The earliest time any point reaches PARAMS.level along MOTION. Allocation-free.
  ImpactResult Earliest(const BlendMotion& motion, const ImpactParams& params);

  // The points whose distance at pose X_AB (B in A) is at most BAND, written to OUT (at most
  // CAPACITY, the rest left out). It descends a level only when all of that level's nodes fit in
  // NODE_BUDGET (<= 0: no limit) beside those visited; where the next level does not fit, this
  // level's nodes within the band are reported as their own point at their subtree's lower
  // bound d(c) - λ r, and *DEGRADED is set. Adds the nodes visited to *VISITED. Returns how many
  // were written.
  //
  // It keeps the distance of every node it visits: an Earliest whose motion starts at X_AB
  // (the proxy's constrained step after its active set) reads them instead of looking them up
  // again, for every node that starts at t = 0 (all those within 1.5 level of B, which Near
  // visited: its band is twice the level). Near and Earliest place a point at the same pose by
  // the same arithmetic, so the distances are the very ones Earliest would compute.
  int Near(const Pose& X_AB, double band, double lipschitz, std::int64_t node_budget, NearPoint* out, int capacity,
           std::int64_t* visited, bool* degraded);

 private:
  // The distance Near kept for NODE, or null when the latest Near did not visit it or ran at
  // another pose than R0, O0.
  const float* StartDistance(std::int32_t node) const {
    return start_valid_ && start_stamp_[std::size_t(node)] == stamp_ ? &start_d_[std::size_t(node)] : nullptr;
  }

  std::shared_ptr<const Pointshell> shell_;
  std::shared_ptr<const DistanceField> field_;
  std::vector<std::int32_t> queue_, next_;  // breadth-first node queues
  std::vector<double> queue_t_, next_t_;    // each node's start time
  // Each node's distance at its start time when its parent, the same point one level up,
  // looked it up there (NaN when not): a first child does not look it up again.
  std::vector<float> queue_d_, next_d_;
  std::vector<std::int32_t> band_;  // Near: the nodes of the current level within the band
  // Each queued node's advanced time and its distance there (Earliest, one level at a time).
  std::vector<double> adv_t_;
  std::vector<float> adv_d_;
  // The latest Near: its pose, and per node the distance there, valid where the node's stamp is
  // stamp_. start_valid_ is set by Earliest for the one motion it is running.
  Eigen::Quaterniond near_R_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d near_o_ = Eigen::Vector3d::Zero();
  bool near_kept_ = false, start_valid_ = false;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> start_stamp_;
  std::vector<float> start_d_;
};

}  // namespace contactlab
