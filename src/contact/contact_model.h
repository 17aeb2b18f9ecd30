// The common contact interface (DESIGN.md): every model — the paper's pointshell-vs-field
// model and each baseline — answers one query per haptic cycle through it.
//
// Conventions. Body A is the pointshell (or first) body, B the distance-field (or second)
// body. The result is the wrench ON B, torque about B's origin, world frame, SI units. Its
// gradient K_B is d(wrench on B)/d(pose of B) for the perturbation X_WB -> (exp([dθ]) R_WB,
// p_WB + dx) with dx, dθ in world coordinates, ordered (dx, dθ) and (force, torque).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string_view>

#include "deform/reduced_state.h"
#include "geometry/pose.h"

namespace contactlab {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // newtons
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // newton metres
  Vector6d AsVector() const {
    Vector6d v;
    v << force, torque;
    return v;
  }
};

struct ContactStats {
  std::int32_t points_in_contact = 0;  // points (or contacts) contributing force
  std::int64_t nodes_visited = 0;      // tree nodes / points / primitives examined
  std::int32_t level_rendered = -1;    // deepest tree level completed (-1: not a tree model)
  std::int32_t nodes_skipped_coherence = 0;
  double max_penetration = 0;          // largest |d| over contributing points, metres
  double stiffness_scale = 1;          // L / l when l >= L points touch, else 1
};

struct ContactQuery {
  Pose X_WA;                            // world pose of body A
  Pose X_WB;                            // world pose of body B
  const ReducedState* q_A = nullptr;    // deformation of A (r entries), null: at rest
  const ReducedState* q_B = nullptr;    // deformation of B, null when rigid
  // Out: the reduced contact force on deformable A, sum_i U_i^T F_i over its points' forces
  // F_i (A's body frame), r entries. Written by models that deform A; null: not wanted.
  ReducedVector* reduced_force_A = nullptr;
  // Out, with reduced_force_A: its derivative -d(reduced force)/dq (r x r, symmetric positive
  // semidefinite) under the sec. 5 halfspace rule, k sum_i (U_i^T N_i)(U_i^T N_i)^T, for an
  // integrator that treats the contact force linearly implicitly. Null: not wanted.
  ReducedMatrix* reduced_stiffness_A = nullptr;
  // Out, for a deformable B rendered through its deformed distance field (paper sec. 4.2): the
  // reduced contact force on B, sum of U_p^T F over its contact forces F (B's frame), each
  // applied at the nearest proxy p (r_B entries), and with reduced_force_B its stiffness
  // -d(reduced force)/dq_B under the halfspace rule. Null: not wanted.
  ReducedVector* reduced_force_B = nullptr;
  ReducedMatrix* reduced_stiffness_B = nullptr;
  // When both bodies deform and each integrator steps on its own with the other held fixed
  // (staggered), the gap closes from both sides while each linearly implicit step sees only
  // its own side: pass each integrator kStaggeredStiffnessFactor times its stiffness, exact for
  // equal compliances and overdamped otherwise (without it two pressed bodies oscillate).
  static constexpr double kStaggeredStiffnessFactor = 2.0;
  std::int64_t cycle = 0;               // haptic cycle index, for temporal coherence
  std::int64_t node_budget = 0;         // graceful degradation; <= 0 means unlimited
};

struct ContactResult {
  Wrench on_B;
  Matrix6d K_B = Matrix6d::Zero();
  ContactStats stats;
};

// What one pointshell point did in a model's latest query (for display, as the paper's Fig. 2).
enum class PointState : std::uint8_t {
  kNotEvaluated = 0,  // culled with its subtree, asleep under coherence, or below the level rendered
  kClear = 1,         // evaluated, d >= 0
  kInContact = 2,     // evaluated, d < 0: carries force
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::string_view name() const = 0;
  // One haptic cycle. Implementations allocate nothing and throw nothing here.
  virtual ContactResult Evaluate(const ContactQuery& query) = 0;
  // Forgets temporal state (coherence, level-of-detail hysteresis).
  virtual void Reset() = 0;
  // For display: the states of body A's pointshell points POINTS (indices into the shell the
  // model traverses) in the latest Evaluate, whose query was QUERY, written to OUT[0..k).
  // Returns k, how many leading points were written: fewer than asked when a model bounds its
  // work per call (it then re-evaluates distances), 0 when it has no pointshell. Call it after
  // Evaluate and before the query's deformations change. Allocation-free, throws nothing.
  virtual int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) {
    (void)query, (void)points, (void)out;
    return 0;
  }
};

}  // namespace contactlab
