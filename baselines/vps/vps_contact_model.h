// The Voxmap-PointShell (VPS) contact model as a baseline behind the common contact interface:
// McNeely, Puterbaugh & Troy, "Six degree-of-freedom haptic rendering using voxel sampling",
// SIGGRAPH 1999 (sec. 4: voxmap, pointshell, tangent-plane force model), with the 8-bit
// distance-to-contact voxmap for temporal coherence of McNeely, Puterbaugh & Troy 2006,
// "Voxel-based 6-DOF haptic rendering improvements" (Haptics-e 3(7), sec. 3).
//
// Body A carries the pointshell (points with inward unit normals N, body frame), body B the
// voxmap built from B's distance field; the structure mirrors PointshellContactModel.
//
// Force model (per point P, in B's frame, voxel of P with centre c, voxel side v), chosen by
// VpsContactParams::voxmap (scene key `voxmap`):
//   layered (default; the distance-layered voxmap of DLR's VPS, Sagardia, Hulin et al.):
//                   every surface and interior voxel carries its centre's depth D(c) = -d(c)
//                   in voxel layers and B's outward normal n(c) = grad d / |grad d|, both from
//                   B's field (voxel_depths.h). depth = D(c) + (c - p) . n(c): the depth below the
//                   plane through the surface point nearest c, exact for a plane, continuous
//                   across voxel faces there, growing with depth through the whole interior
//                   (DLR's interpolated voxmap distance); the force is along P's normal N, as
//                   in DLR's VPS and the paper's model, so it never turns against the point
//                   where n(c) flips across a thin wall or B's medial axis;
//   surface (McNeely et al. 1999, kept for the record):
//     surface voxel   depth = max(0, (c - p) . N): the depth of P below the tangent plane
//                     through c perpendicular to P's normal N (N points into A, so depth grows
//                     as P goes deeper into B); at most v sqrt(3) / 2 inside the voxel;
//     interior voxel  depth = interior_depth, by default half the voxel diagonal v sqrt(3) / 2,
//                     the largest depth a surface voxel can produce (McNeely 1999 bound the
//                     force of points that reach the interior by the surface-voxel maximum);
//   proximity/free  no force (McNeely 1999 used proximity voxels for a velocity-dependent
//                   pre-contact braking force, which a static wrench query has no use for).
// A point with depth > 0 adds F_B = -k depth N to B (ContactAccumulator::Add(p_B, N_B, -depth,
// N_B)), k = k_C scaled by L / l when l >= L points touch (as the paper's model); torque about
// B's origin; K_B by the paper's halfspace rule (sec. 5) with N (layered: the exact derivative
// within a voxel where N = n(c), as the paper's model's where N is the field's normal).
// The surface model's force jumps when a point crosses a voxel face (c jumps by v): the known
// VPS artefact. It also has a dead band (measured on data/scenes/sphere-on-plate.yaml, see
// VpsContactModel::Evaluate): a surface voxel counts only points below its centre, and the
// interior starts a whole surface layer below the surface.
//
// Time budget (graceful degradation): the query's node_budget counts the points looked at (the
// coherence's skipped points cost next to nothing and are not counted). With a budget the points
// are visited in the bit-reversed order of their index, computed once at construction: each
// level of a shell is ordered along a Morton curve, so its prefix would be one region, and the
// bit-reversed order spreads the first m evenly over it. Its spread reads cost more per point
// than visiting the points in order, which a budget chosen for a time must allow for; runs of
// 16 consecutive points (a cache line of each array) cost less but sample patches: 9-26 % force
// error at 10,000 points 20 mm deep, against 1.3-3.9 % point by point. Past the budget the loop
// stops: the points it reached stand for the whole, their sums counted n / reached times
// (ContactAccumulator::Scale). The same points each cycle, so the answer does not flicker.
// stats.degraded = ceil(log2(n / reached)): the halvings of the share of points tested. Points
// not reached keep their coherence state and are looked at again when the budget allows.
//
// Contacts (KeepContacts / LatestContacts): one per point with depth > 0, as many as
// stats.points_in_contact: the point's world position, the direction of its force on B, -N in
// the world, and its depth as the force model above takes it (metres).
//
// Friction (contact/friction.h; params.friction): each point with depth > 0 holds an anchor in
// B's frame from its first touch until its depth is 0 again, indexed by the point, with depth
// weight `depth` and gradient N (the halfspace rule, as the force). Under a budget the points
// the loop does not reach lose their anchors and start afresh when it reaches them again.
//
// Temporal coherence (optional, McNeely 2006): a point found in a free voxel n >= 2 layers
// from the nearest contact voxel cannot touch before it has moved (n - 1) v, so it is not
// looked at again for ceil((n - 1) v / (max_point_speed * cycle_seconds)) cycles (a point
// outside the voxmap: its distance to the voxmap box instead). Exact (identical wrench) as
// long as no point of A moves faster than max_point_speed relative to B.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "baselines/vps/voxel_depths.h"
#include "baselines/vps/voxmap.h"
#include "baselines/vps/vps_params.h"
#include "baselines/vps/wide_voxmap.h"
#include "contact/contact_model.h"
#include "contact/contact_recorder.h"
#include "contact/friction.h"
#include "contact/penalty_params.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

struct VpsContactParams {
  PenaltyParams penalty;         // k_C per point and the L / l scaling, as the paper's model
  double voxel_size = 0;         // voxmap voxel side, metres; <= 0: B's field spacing
  VpsVoxmap voxmap = VpsVoxmap::kLayered;  // force model: distance layers, or the 1999 surface layer
  double interior_depth = -1;    // surface model: depth of a point in an interior voxel, metres; < 0: v sqrt(3)/2
  bool coherence = false;        // temporal coherence through the 8-bit voxmap
  double max_point_speed = 1.0;  // m/s, largest speed of any pointshell point relative to B
  double cycle_seconds = 1e-3;   // duration of one haptic cycle, seconds
  FrictionParams friction;       // off by default
};

// What the model holds, for reports and experiments.
struct VpsModelInfo {
  double voxel_size = 0;                       // metres
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();  // voxels per axis
  std::int64_t voxels = 0;
  std::int64_t free = 0, proximity = 0, surface = 0, interior = 0;  // voxel counts
  std::size_t voxmap_bytes = 0;       // 2-bit voxmap: ceil(voxels / 4)
  std::size_t wide_voxmap_bytes = 0;  // 8-bit voxmap: voxels (0 when coherence is off)
  std::size_t depth_map_bytes = 0;    // layered voxmap: 4 bytes a voxel (0 for the surface model)
  std::int32_t points = 0;            // pointshell points rendered
  std::size_t pointshell_bytes = 0;   // 6 floats per point
  double interior_depth = 0;          // surface model: metres
};

class VpsContactModel final : public ContactModel {
 public:
  // NAME is what name() reports ("vps", "vps-repulsion"). SHELL is A's pointshell (every
  // point of it is rendered, whatever its levels); FIELD is B's distance field, from which
  // the voxmap (and, with coherence, the 8-bit voxmap) is built here. Throws Error for
  // an empty shell or field, k_C < 0 or not finite, a non-positive speed or cycle time, and
  // the errors of BuildVoxmap.
  VpsContactModel(std::string name, std::shared_ptr<const Pointshell> shell,
                  std::shared_ptr<const DistanceField> field, const VpsContactParams& params);

  std::string_view name() const override { return name_; }
  // One haptic cycle: allocation-free, throws nothing. query.node_budget (> 0) bounds the
  // points looked at (see the top of this file).
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // Coherence only: friction anchors are no such shortcut and stay.
  void ResetCoherence() override;
  // The points with depth > 0 (see the top of this file), recorded during Evaluate.
  bool KeepContacts(int max_contacts) override {
    contacts_.Keep(max_contacts, false, params_.friction.on());
    return true;
  }
  void LatestContacts(ContactList* out) const override { contacts_.Fill(X_WB_contacts_, 1.0, out); }

  const VpsContactParams& params() const { return params_; }
  const Pointshell& shell() const { return *shell_; }
  const Voxmap& voxmap() const { return voxmap_; }
  const WideVoxmap& wide_voxmap() const { return wide_; }  // empty when coherence is off
  const VoxelDepthMap& depth_map() const { return depths_; }  // empty for the surface model
  VpsModelInfo info() const;

 private:
  // Point I in contact at P_B with unit normal N_B and DEPTH > 0 (B's frame), friction on: its
  // anchor and terms, into SUMS and the contacts kept.
  void AddFriction(int i, const Eigen::Vector3d& p_B, const Eigen::Vector3d& N_B, double depth, FrictionSums* sums);

  std::string name_;
  std::shared_ptr<const Pointshell> shell_;
  VpsContactParams params_;
  Voxmap voxmap_;
  WideVoxmap wide_;
  VoxelDepthMap depths_;   // layered model only
  double interior_depth_;  // metres
  float box_hi_[3];        // upper corner of the voxmap box (B frame)

  // Scratch sized once at construction.
  std::vector<std::int64_t> next_check_;  // (#P) temporal coherence: first cycle to look again
  std::vector<std::int32_t> budget_order_;  // (#P) the points' indices in bit-reversed order (a budget's)
  FrictionAnchors anchors_;   // (#P) friction on: each point's anchor
  ContactRecorder contacts_;  // the latest Evaluate's contacts, B's frame, when kept
  Pose X_WB_contacts_;        // and B's pose then
};

}  // namespace contactlab
