// Closed-loop stability of the haptic display with a real contact model on a real scene
// (Barbič & James 2008, sec. 5): the simulated hand (haptics/sim_device.h, a handle mass pulled
// by a spring-damper hand toward a scripted target) drives the scene's field body H through
// static virtual coupling with quasi-static damping and the safety filter, at the scene's rate
// (model.cycle_seconds) in simulated time, against the scene's pointshell body A held static. Three motions: push into contact,
// push and slide along the surface, and a hard tilted push (an edge or corner of H leading,
// 30 mm past first touch, so the hand asks for more than the device's 8 N). Each run measures
// the passivity observer (the work the device wrench does on the handle, as in
// tests/haptics/closed_loop_test.cc) and the oscillation left while the hand holds still in
// contact.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>

#include "contact/contact_model.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "geometry/pose.h"
#include "haptics/haptic_cycle.h"

namespace contactlab {

enum class LoopMotion { kPush, kSlide, kCorner };
const char* LoopMotionName(LoopMotion motion);

// Where the hand goes on one scene: H's poses touching A (0.5 mm deep, found with the paper's
// model by TouchAlong) for a straight and for a tilted approach, and the directions.
struct ClosedLoopScene {
  Pose X_WH_touch;                // H touching A approaching along `approach`
  Pose X_WH_touch_tilted;         // H tilted by 30 degrees, touching A along `corner_approach`
  Eigen::Vector3d approach = Eigen::Vector3d::UnitX();         // unit, H's motion toward A
  Eigen::Vector3d corner_approach = Eigen::Vector3d::UnitX();  // unit
  Eigen::Vector3d slide = Eigen::Vector3d::UnitY();            // unit, perpendicular to approach
  // The scene's haptic cycle (scene/scene_query.h SceneCycleConfig: A's static pose X_WA, node
  // budget, coherence guard, rate); each run sets its coupling and the bodies' dynamics on a copy.
  HapticCycleConfig cycle;
};

// Approach: from H's scene pose straight toward A's origin; slide: perpendicular to it (world y
// projected off the approach); the tilted approach comes in 30 degrees off the straight one
// (rotated about the slide direction's normal), with H rotated 30 degrees about the same axis.
// Throws Error naming the scene when the bodies never touch.
ClosedLoopScene MakeClosedLoopScene(const Scene& scene, SceneAssets& assets);

struct ClosedLoopCase {
  LoopMotion motion = LoopMotion::kPush;
  double k_vc = 1000;          // N/m, swept
  double k_vc_rot = 1.0;       // N m/rad, held at the coupling's default while k_vc is swept
  double push_depth = 0.008;   // m past first touch the hand's target goes (kCorner: corner_depth)
  double corner_depth = 0.030;
  double slide_distance = 0.015;  // m (kSlide)
  double alpha = 0.5;             // quasi-static damping of a 1 ms cycle
  bool alpha_per_cycle = false;   // true: alpha per cycle at any rate (HapticCycleConfig::alpha_per_cycle)
};

struct ClosedLoopMetrics {
  // Passivity observer: ∫ (F·v + T·ω) dt of the device wrench on the handle over the whole run
  // (the hand starts and ends at rest in free space). Positive: the loop put energy into the hand.
  double energy_into_hand = 0;   // J
  double peak_stored_energy = 0; // J, largest coupling-spring energy 0.5|F|²/k_vc + 0.5|T|²/k_rot seen
  // Oscillation while the hand's target holds still in contact: RMS deviation of H's position and
  // of the device force from their least-squares line (a slow drift is not an oscillation), over
  // the first and the last 200 ms of the hold.
  double early_position_rms = 0, late_position_rms = 0;  // m
  double early_force_rms = 0, late_force_rms = 0;        // N
  double hold_force_mean = 0;      // N, |mean device force| over the last 200 ms (pressed = nonzero)
  double max_contact_force = 0;    // N
  double max_device_force = 0;     // N, after the safety filter
  double max_force_jump = 0;       // N, largest change of the device force from one cycle to the next
  double rate_hz = 0;              // the loop's rate, 1 / the cycle simulated
  std::int64_t clamped_cycles = 0;     // safety force or torque clamp
  std::int64_t non_finite_cycles = 0;  // non-finite wrench zeroed by the safety filter
  std::int64_t solve_failures = 0;
  std::int64_t coherence_resets = 0;
  std::int64_t contact_faults = 0;     // queries the model refused (a deformation of the wrong size)
  double max_q_norm = 0;               // largest |q| of a deformable body (0: both rigid)
  int max_points_in_contact = 0;
  int cycles = 0;
  bool finite = true;   // every recorded pose and force finite
  double wall_seconds = 0;

  // The criteria (see closed_loop_stability.cc): passive within max(1e-5 J, 1 % of the peak
  // stored energy); settled when the last 200 ms of the hold move H by < 20 µm RMS and the force
  // by < 0.05 N RMS; stable when finite, without faults (non-finite wrenches, failed solves,
  // refused queries), passive and settled.
  bool passive() const;
  bool settled() const;
  bool stable() const;
};

// Why a run is not stable ("non-finite", "solve failed", "contact faults", "active",
// "oscillates", "active+oscillates"), or "ok".
std::string StabilityVerdict(const ClosedLoopMetrics& m);

// The slowest cycle the study judges: each of its 200 ms windows (the motions' oscillation
// windows) must hold at least 10 cycles, so model.cycle_seconds is at most 0.02 s.
inline constexpr double kClosedLoopMaxCycleSeconds = 0.02;

// Throws Error naming WHERE and the bodies' poses when SCENE gives the study no approach: H (the
// field body) moves toward A's origin, so the two must lie at different positions.
void CheckClosedLoopApproach(const Scene& scene, const std::string& where);

// Runs one closed-loop case: MODEL's body B is H. The model is reset at the start. DYNAMICS
// (MakeSceneDynamics of the scene at where.cycle.cycle_seconds; null or empty: both bodies rigid)
// steps the deformable bodies at the end of each cycle; they start at rest.
ClosedLoopMetrics RunClosedLoop(ContactModel& model, const ClosedLoopScene& where, const ClosedLoopCase& c,
                                SceneDynamics* dynamics = nullptr);

}  // namespace contactlab
