// "pointshell-ccd": a proxy of body B that never passes through body A (after Xu & Barbič,
// "6-DoF Haptic Rendering Using Continuous Collision Detection between Points and Signed
// Distance Fields", IEEE Trans. Haptics 2017), on the paper's data: A's pointshell against B's
// distance field.
//
// The model keeps a proxy of B (its pose in A's frame) between cycles; Reset forgets it, and
// the next query places it at B. Each cycle, up to `iterations` times:
//   1. the active set: A's points within 2 l of B's surface at the proxy (l: the contact
//      offset), each a halfspace constraint on the proxy's twist ξ = (v, w) (A's frame, rotation
//      about B's origin): d_i - g_i·v - ((p_i - o) x g_i)·w >= l;
//   2. the step: the twist closest to the query's pose of B in the coupling's metric
//      M = diag(k, k, k, k_rot, k_rot, k_rot) subject to those constraints, by projected
//      Gauss-Seidel on the multipliers (a 6-vector kept in step with them);
//   3. the move: along that twist only as far as the earliest time any point reaches l
//      (time_of_impact.h); when nothing is reached the step is done and so is the cycle. The
//      impact search starts where the active set's search ran and takes the distances it
//      looked up there (every node within 1.5 l of B starts the motion at t = 0) rather than
//      looking them up again.
// A cycle's cost grows with the nodes the two searches visit near B (those within about 2 l of
// B, and those whose bound reaches l along the step) and, most of all, with the steps of the
// points in sliding contact: each advances by l / 2 to l of its path per lookup, so their
// lookups grow with the active points times the proxy's travel over l (up to 64 each a step),
// and with the constrained steps the cycle takes.
// The wrench on B is the spring between proxy and B: F = k (p_WP - p_WB), τ = k_rot φ with
// φ = log(R_WP R_WB^T) (about B's origin), unsaturated. K_B is its derivative with the proxy
// sliding: the proxy follows B along every direction no pushing constraint blocks, so
// K_B = -M^½ P M^½ with P the projector onto the span of M^-½ J_a^T (J_a: the constraints
// the step ends on, pushing or tight). Free space: proxy = B, zero wrench, K_B = 0.
//
// Contacts (KeepContacts / LatestContacts): the pushing constraints of the cycle's last step,
// as many as stats.points_in_contact: A's point (world), the direction in which it pushes the
// proxy and so B, -∇d normalised (B's field gradient at the point, world), and the point's depth
// in B at the query's pose of B, max(0, -d) (the proxy holds it at the offset l outside, so
// this is how far the device has pressed past the proxy there; 0 where it has not).
//
// Graceful degradation: the scene's node budget bounds the cycle's work, counted in lookups: a
// node visited by either search and a step of a node or point along the motion are one each, and
// eight constraint updates of the solve (one point in one sweep) are one. The searches share it
// (past it a node is not expanded and stands for its subtree conservatively, and the nodes and
// points in flight stop: the proxy stops early, never passes through); the solve takes the
// sweeps it leaves, at least one, and no constrained step starts once it is spent. stats.degraded
// is 1 when it cut anything; stats.nodes_visited counts the searches' nodes alone.
// Allocation-free and exception-free in Evaluate. Rigid bodies only.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "baselines/pointshell_ccd/time_of_impact.h"
#include "contact/contact_model.h"
#include "contact/contact_recorder.h"

namespace contactlab {

// The smallest offset l, in cells of B's field, at which the proxy follows a contact. A point
// in contact advances by at least l / 2 a step, 64 steps a point per constrained step
// (time_of_impact.h), so the proxy slides at most about a hundred offsets a cycle: at 0.01
// cells of a 2 mm grid it follows a face sliding 0.5 mm a cycle, at 0.001 it lags with 300 N of
// tangential drag, and at 1e-12 it stalled at B's pose (6.4e-9 N instead of 58.5 N, 28 ms a
// query). The scene row proxy_offset (register_pointshell_ccd.cc) starts here.
constexpr double kMinProxyOffsetCells = 0.01;

struct PointshellCcdParams {
  double stiffness = 1e4;       // k, N/m
  double rot_stiffness = 1;     // k_rot, N m/rad
  double offset = 1e-4;         // l, metres: points stop at this distance from B's surface
                                // (at least kMinProxyOffsetCells of B's field)
  int iterations = 4;           // constrained steps per cycle
  double lipschitz = 1;         // λ, bound on |∇d|
  int max_constraints = 8192;   // active points kept per step (the nearest-first are not sorted)

  // Throws Error naming WHERE when a value is out of range.
  void Check(std::string_view where) const;
};

class PointshellCcdModel final : public ContactModel {
 public:
  PointshellCcdModel(std::shared_ptr<const Pointshell> shell_A, std::shared_ptr<const DistanceField> field_B,
                     const PointshellCcdParams& params);

  std::string_view name() const override { return "pointshell-ccd"; }
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // The proxy is not a coherence shortcut: a motion faster than max_point_speed keeps it.
  void ResetCoherence() override {}
  bool Proxy(Pose* X_WB_proxy) const override;
  // The pushing constraints (see the top of this file), recorded at the end of Evaluate.
  bool KeepContacts(int max_contacts) override {
    contacts_.Keep(max_contacts);
    return true;
  }
  void LatestContacts(ContactList* out) const override { contacts_.Fill(Pose(), 1.0, out); }

  const PointshellCcdParams& params() const { return params_; }

 private:
  // The parts of one constrained step over the N active points in near_ (A's frame); (V, W) is
  // the proxy's twist, starting at the straight step to B.
  // Loads each point's moment about the proxy's origin O and inverse diagonal, and its
  // multiplier warm-started from the point's latest one, applied to (V, W). *DEEPEST: the
  // deepest penetration. Returns the largest violation l - d_i.
  double LoadConstraints(int n, const Eigen::Vector3d& o, Eigen::Vector3d* v, Eigen::Vector3d* w, double* deepest);
  // Projected Gauss-Seidel sweeps on the multipliers, at most MAX_SWEEPS, (V, W) kept in step
  // with them. Returns the sweeps made; *CONVERGED: whether the last left no violation.
  int SolveMultipliers(int n, int max_sweeps, Eigen::Vector3d* v, Eigen::Vector3d* w, bool* converged);
  // Keeps the multipliers per point for the next step's warm start, forgetting the previous.
  void KeepMultipliers(int n);
  // The constraints the step (V, W) ends on: *G = sum of u u^T over them, u = M^-1/2 J^T.
  // Returns how many of them push (carry a multiplier).
  int TightConstraints(int n, const Eigen::Vector3d& v, const Eigen::Vector3d& w, Matrix6d* G) const;

  ImpactSearch search_;
  PointshellCcdParams params_;
  bool has_proxy_ = false;
  Pose X_AP_;             // the proxy of B in A's frame
  Pose X_WA_last_;        // A's pose in the latest query (for Proxy)
  std::vector<NearPoint> near_;
  std::vector<Eigen::Vector3d> moment_;  // (p_i - o) x g_i of each active point
  std::vector<double> multiplier_, inv_diag_;
  // The latest multiplier of each point (warm start: in steady contact one sweep suffices), and
  // the points it was written for.
  std::vector<double> point_multiplier_;
  std::vector<std::int32_t> warm_points_;
  int warm_count_ = 0;
  ContactRecorder contacts_;  // the latest Evaluate's pushing constraints, world frame, when kept
};

}  // namespace contactlab
