// One haptic cycle (Barbič & James 2008, sec. 5): read the manipulandum, evaluate contact at
// the simulated pose, solve the static virtual coupling, filter for safety, write the wrench.
// No threads and no clock here: the real-time loop (haptic_loop.h) and simulated-time tests
// both drive Step(now).
#pragma once

#include <cstdint>

#include "contact/coherence_guard.h"
#include "contact/contact_model.h"
#include "deform/body_dynamics.h"
#include "haptics/contact_cycle.h"
#include "haptics/contact_point_marks.h"
#include "haptics/haptic_device.h"
#include "haptics/safety_filter.h"
#include "haptics/virtual_coupling.h"

namespace contactlab {

struct HapticCycleConfig {
  // The coupling; its alpha is the paper's quasi-static damping of a 1 ms cycle, which the cycle
  // turns into its own with CouplingAtRate(coupling, cycle_seconds).
  VirtualCouplingParams coupling;
  // true: the coupling's alpha is applied per cycle as given, whatever the rate (the paper's rule
  // read literally; at 10 kHz it makes H follow the device ten times faster in time). For studies
  // of that choice; sessions keep false.
  bool alpha_per_cycle = false;
  // Safety limits; max_force / max_torque <= 0 mean "use the device's capabilities".
  SafetyParams safety{.max_force = 0, .max_torque = 0};
  Pose X_WA;                       // pose of the static contact body A (world)
  std::int64_t node_budget = 0;    // passed to the contact model; <= 0 means unlimited
  // Body A's dynamics when A is a deformable pointshell (paper sec. 4): its deformation is held
  // fixed during the contact query, then stepped once at the end of the cycle with the reduced
  // contact force (and stiffness), as the object's coupling mode and staggering say. Null: A is
  // rigid. Must outlive the cycle (scene/scene_assets.h MakeSceneDynamics builds it).
  BodyDynamics* dynamics_A = nullptr;
  // The haptic body H's own dynamics when H is a deformable field body (paper sec. 4.2 and 5,
  // "the deformable haptic object"): three configurations — the manipulandum, H's rigid
  // simulation pose (the virtual coupling acts on it alone) and that pose plus the
  // deformation, which the contact query sees. Held fixed during the query, stepped at the end
  // of the cycle with the reduced contact force on H, decoupled from H's rigid motion. Null:
  // H is rigid. Must outlive the cycle.
  BodyDynamics* dynamics_B = nullptr;
  // Guard of the contact model's temporal coherence (paper sec. 3.4): the coherence assumes
  // no point of A moves faster than max_point_speed relative to B, i.e. no more than
  // max_point_speed * cycle_seconds per cycle. Each cycle measures the motion of H between
  // consecutive contact queries, |dp| + |dtheta| * body_radius_H over cycle_seconds, and when it
  // exceeds max_point_speed resets the model (a full traversal this cycle) and counts the
  // cycle (contact/coherence_guard.h, which the experiment runner uses too). max_point_speed
  // <= 0 disables the guard.
  double max_point_speed = 0;      // m/s (the scene's model.max_point_speed)
  double cycle_seconds = 1e-3;     // s, the cycle the coherence counts in (model.cycle_seconds)
  double body_radius_H = 0;        // m, bounding radius of H's geometry about its origin
                                   // (TriangleMesh::MaxVertexRadius of H's mesh)
  // The live view's per-point contact marks (contact_point_marks.h), updated after each
  // contact query; null (no view): nothing is done. Must outlive the cycle.
  ContactPointMarks* point_marks = nullptr;
};

// What one cycle did; trivially copyable so it can travel through an SpscRing.
struct CycleRecord {
  std::int64_t cycle = 0;
  std::int64_t now_ns = 0;            // loop clock at the start of the cycle
  std::int64_t device_timestamp_ns = 0;
  std::uint64_t device_sequence = 0;
  std::uint32_t buttons = 0;
  std::uint32_t safety_flags = 0;     // SafetyFlag bits
  bool new_sample = false;
  bool solve_ok = true;
  bool coherence_reset = false;       // H moved faster than max_point_speed: the model was reset
  double point_speed = 0;             // measured bound on the speed of H's points, m/s
  std::int32_t points_in_contact = 0;
  std::int32_t level_rendered = -1;   // deepest tree level the contact model rendered
  std::int64_t nodes_visited = 0;
  std::int64_t work_ns = 0;           // time the cycle took (set by the loop), ns
  std::int64_t cpu_ns = 0;            // the loop thread's CPU time over that work (set by the loop), ns
  std::int64_t step_ns = 0;           // the deformation steps within it (deformable A and/or H), ns
  double q_norm = 0;                  // |q| of body A after the step (deformable A)
  double q_norm_B = 0;                // |q| of H after the step (deformable H)
  double p_WD[3] = {0, 0, 0};         // device position, m
  double q_WD[4] = {1, 0, 0, 0};      // device orientation (w, x, y, z)
  double p_WH[3] = {0, 0, 0};         // simulated body position, m
  double q_WH[4] = {1, 0, 0, 0};
  // A contact model's proxy of H (ContactModel::Proxy, pointshell-ccd: where H is held outside
  // the other body), world frame; has_proxy false for models without one.
  bool has_proxy = false;
  double p_WP[3] = {0, 0, 0};
  double q_WP[4] = {1, 0, 0, 0};
  double contact_force[3] = {0, 0, 0};    // contact force on H, N
  double device_force[3] = {0, 0, 0};     // force written to the device (after safety), N
  double device_torque[3] = {0, 0, 0};    // torque written, N m
  std::int64_t coherence_resets = 0;      // such resets so far this session
  // The contact model refused this cycle's query and gave no force (ContactStats::faults: a
  // deformation whose size does not fit its body), or a deformation was not finite (a diverged
  // step: not queried, no force, the body restarted from rest); such cycles so far this session.
  bool contact_fault = false;
  std::int64_t contact_faults = 0;
  DeviceInputStats device_input;          // the device's input counters after this cycle
};

class HapticCycle {
 public:
  // DEVICE must outlive the cycle. MODEL may be null (free space) and must outlive it too;
  // its body B is the haptic body H, body A is static at CONFIG.X_WA. Throws Error when the
  // configuration is invalid.
  HapticCycle(HapticDevice& device, ContactModel* model, const HapticCycleConfig& config);
  HapticCycle(const HapticCycle&) = delete;  // its contact cycle points at its coherence guard
  HapticCycle& operator=(const HapticCycle&) = delete;

  // Starts a session at NOW_NS: reads the device, places H at the device pose, restarts the
  // safety ramp, resets the contact model.
  void Start(std::int64_t now_ns);

  // Runs one cycle at NOW_NS (loop clock, ns). Allocation-free, lock-free, never throws.
  CycleRecord Step(std::int64_t now_ns);

  // Writes a zero wrench (clean stop).
  void WriteZero(std::int64_t now_ns);

  const SafetyFilter& safety() const { return safety_; }
  const StaticVirtualCoupling& coupling() const { return coupling_; }
  const DeviceState& device_state() const { return state_; }
  // Cycles whose measured speed of H exceeded max_point_speed (each reset the model).
  std::int64_t coherence_resets() const { return coherence_.resets(); }
  // Cycles whose contact query the model refused (CycleRecord::contact_fault).
  std::int64_t contact_faults() const { return contact_faults_; }
  HapticDevice& device() { return device_; }

 private:
  HapticDevice& device_;
  ContactModel* model_;
  HapticCycleConfig config_;
  StaticVirtualCoupling coupling_;
  SafetyFilter safety_;
  DeviceState state_;
  std::int64_t last_sample_ns_ = 0;
  std::int64_t cycle_ = 0;
  CoherenceGuard coherence_;  // H's motion against the model's max_point_speed
  ContactCycle contact_cycle_;  // the guard, the deformations and the query (contact_cycle.h)
  std::int64_t contact_faults_ = 0;
};

}  // namespace contactlab
