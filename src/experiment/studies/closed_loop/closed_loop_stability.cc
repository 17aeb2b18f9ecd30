// Closed-loop stability with a real contact model on a real scene (Barbič & James 2008, sec. 5).
#include "experiment/studies/closed_loop/closed_loop_stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "scene/contact_placement.h"
#include "haptics/haptic_cycle.h"
#include "scene/scene_query.h"
#include "haptics/safety_filter.h"
#include "haptics/sim_device.h"

namespace contactlab {
namespace {

constexpr double kStartBack = 0.010;     // m: the hand starts this far back from first touch
constexpr double kTouchDepth = 0.0005;   // m: "touching" = 0.5 mm deep (paper's model)
constexpr double kTiltRadians = 30.0 * M_PI / 180.0;
constexpr double kPushBegin = 0.1, kPushEnd = 0.5;   // s
constexpr double kSlideBegin = 0.6, kSlideEnd = 1.4; // s
constexpr double kHold = 0.6;                        // s the target stays still in contact
constexpr double kWindow = 0.2;                      // s, oscillation windows
static_assert(kWindow / kClosedLoopMaxCycleSeconds >= 10 - 1e-9, "each window holds at least 10 cycles");
constexpr double kLift = 0.3, kRest = 0.3;           // s

double Smooth(double t, double t0, double t1) {
  if (t <= t0) return 0;
  if (t >= t1) return 1;
  return 0.5 - 0.5 * std::cos(M_PI * (t - t0) / (t1 - t0));
}

// RMS deviation of equally spaced 3-vector samples from their least-squares line: the
// oscillation about a slow drift (H creeping along a surface while the handle settles is not
// an oscillation).
double RmsAboutTrend(const std::vector<Eigen::Vector3d>& xs) {
  const std::size_t n = xs.size();
  if (n < 3) return 0;
  const double t_mean = 0.5 * double(n - 1);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : xs) mean += x;
  mean /= double(n);
  Eigen::Vector3d cov = Eigen::Vector3d::Zero();
  double var_t = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dt = double(i) - t_mean;
    cov += dt * (xs[i] - mean);
    var_t += dt * dt;
  }
  const Eigen::Vector3d slope = cov / var_t;
  double s = 0;
  for (std::size_t i = 0; i < n; ++i) s += (xs[i] - mean - (double(i) - t_mean) * slope).squaredNorm();
  return std::sqrt(s / double(n));
}

}  // namespace

const char* LoopMotionName(LoopMotion motion) {
  switch (motion) {
    case LoopMotion::kPush: return "push";
    case LoopMotion::kSlide: return "slide";
    case LoopMotion::kCorner: return "corner";
  }
  return "?";
}

void CheckClosedLoopApproach(const Scene& scene, const std::string& where) {
  const Eigen::Vector3d gap = scene.pointshell_body.pose.translation - scene.field_body.pose.translation;
  if (!(gap.norm() > 0) || !gap.allFinite()) {
    Fail(where, "bodies' pose: the closed-loop study moves the field body '" + scene.field_body.name +
                    "' toward the origin of the pointshell body '" + scene.pointshell_body.name +
                    "', and the two lie at one position: place them apart along the approach");
  }
}

ClosedLoopScene MakeClosedLoopScene(const Scene& scene, SceneAssets& assets) {
  CheckClosedLoopApproach(scene, scene.file.empty() ? scene.name : scene.file);
  ClosedLoopScene w;
  w.cycle = SceneCycleConfig(scene, assets, nullptr);
  const Pose& X_WA = w.cycle.X_WA;
  const Pose X_WH0 = scene.field_body.pose;
  w.approach = (X_WA.translation - X_WH0.translation).normalized();
  Eigen::Vector3d s = Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY().dot(w.approach) * w.approach;
  if (s.norm() < 1e-6) s = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(w.approach) * w.approach;
  w.slide = s.normalized();
  const std::string where = scene.name + ": closed-loop poses";
  w.X_WH_touch = TouchAlong(scene, assets, true, X_WA, X_WH0, w.approach, kTouchDepth, where);
  // Tilted: H rotated about the axis normal to approach and slide, approaching 30 degrees off.
  const Eigen::Vector3d axis = w.approach.cross(w.slide).normalized();
  const Eigen::AngleAxisd tilt(kTiltRadians, axis);
  w.corner_approach = (tilt * w.approach).normalized();
  Pose tilted = X_WH0;
  tilted.rotation = (Eigen::Quaterniond(tilt) * X_WH0.rotation).normalized();
  // Start back along the tilted approach so the line of motion still passes near A's origin.
  tilted.translation = X_WA.translation - (X_WH0.translation - X_WA.translation).norm() * w.corner_approach;
  w.X_WH_touch_tilted = TouchAlong(scene, assets, true, X_WA, tilted, w.corner_approach, kTouchDepth, where);
  return w;
}

bool ClosedLoopMetrics::passive() const {
  return energy_into_hand <= std::max(1e-6, 0.01 * peak_stored_energy);
}
bool ClosedLoopMetrics::settled() const { return late_position_rms < 20e-6 && late_force_rms < 0.05; }
bool ClosedLoopMetrics::stable() const {
  return finite && non_finite_cycles == 0 && solve_failures == 0 && contact_faults == 0 && passive() && settled();
}

std::string StabilityVerdict(const ClosedLoopMetrics& m) {
  if (!m.finite || m.non_finite_cycles > 0) return "non-finite";
  if (m.solve_failures > 0) return "solve failed";
  if (m.contact_faults > 0) return "contact faults";
  std::string r;
  if (!m.passive()) r = "active";
  if (!m.settled()) r += r.empty() ? "oscillates" : "+oscillates";
  return r.empty() ? "ok" : r;
}

ClosedLoopMetrics RunClosedLoop(ContactModel& model, const ClosedLoopScene& w, const ClosedLoopCase& c,
                                SceneDynamics* dynamics) {
  const auto wall0 = std::chrono::steady_clock::now();
  const bool corner = c.motion == LoopMotion::kCorner;
  const bool slide = c.motion == LoopMotion::kSlide;
  const Eigen::Vector3d dir = corner ? w.corner_approach : w.approach;
  const Pose touch = corner ? w.X_WH_touch_tilted : w.X_WH_touch;
  const double depth = corner ? c.corner_depth : c.push_depth;
  const double motion_end = slide ? kSlideEnd : kPushEnd;
  const double hold_end = motion_end + kHold;
  const double run_end = hold_end + kLift + kRest;
  Pose start = touch;
  start.translation -= kStartBack * dir;
  const Eigen::Vector3d slide_offset = slide ? Eigen::Vector3d(c.slide_distance * w.slide) : Eigen::Vector3d::Zero();
  auto target = [=](double t) {
    const double down = Smooth(t, kPushBegin, kPushEnd) - Smooth(t, hold_end, hold_end + kLift);
    Pose X = start;
    X.translation += (kStartBack + depth) * down * dir + Smooth(t, kSlideBegin, kSlideEnd) * slide_offset;
    return X;
  };

  // The hand is integrated at 10 kHz or four times the loop's rate, whichever is finer, so that
  // the device's zero-order hold of each cycle's wrench is resolved at every rate swept.
  SimDeviceParams hand;
  hand.step_seconds = std::min(hand.step_seconds, 0.25 * w.cycle.cycle_seconds);
  SimDevice device(hand, target);
  HapticCycleConfig config = w.cycle;
  config.coupling.k_vc = c.k_vc;
  config.coupling.k_vc_rot = c.k_vc_rot;
  config.coupling.alpha = c.alpha;
  config.alpha_per_cycle = c.alpha_per_cycle;
  config.safety.ramp_seconds = 0.05;  // the hand starts in free space; contact begins at 0.1 s
  if (dynamics != nullptr) {
    config.dynamics_A = dynamics->A.get();
    config.dynamics_B = dynamics->B.get();
  }
  HapticCycle cycle(device, &model, config);
  cycle.Start(0);

  ClosedLoopMetrics m;
  std::vector<Eigen::Vector3d> early_p, early_f, late_p, late_f;
  // One cycle every model.cycle_seconds (the scene's rate), in simulated time.
  const std::int64_t period_ns = std::llround(w.cycle.cycle_seconds * 1e9);
  const double cycle_ms = double(period_ns) / 1e6;  // exactly 1 at 1 kHz: the times below are i ms
  const int n = int(std::lround(run_end * 1000 / cycle_ms));
  Eigen::Vector3d last_f = Eigen::Vector3d::Zero();
  for (int i = 1; i <= n; ++i) {
    const CycleRecord rec = cycle.Step(i * period_ns);
    const double t = 1e-3 * (double(i) * cycle_ms);
    const Eigen::Vector3d p(rec.p_WH[0], rec.p_WH[1], rec.p_WH[2]);
    const Eigen::Vector3d f(rec.device_force[0], rec.device_force[1], rec.device_force[2]);
    const Eigen::Vector3d tq(rec.device_torque[0], rec.device_torque[1], rec.device_torque[2]);
    const Eigen::Vector3d fc(rec.contact_force[0], rec.contact_force[1], rec.contact_force[2]);
    if (!p.allFinite() || !f.allFinite() || !tq.allFinite() || !fc.allFinite()) m.finite = false;
    if (rec.safety_flags & (kSafetyForceClamped | kSafetyTorqueClamped)) ++m.clamped_cycles;
    if (rec.safety_flags & kSafetyNonFinite) ++m.non_finite_cycles;
    if (!rec.solve_ok) ++m.solve_failures;
    m.max_points_in_contact = std::max(m.max_points_in_contact, rec.points_in_contact);
    m.max_q_norm = std::max({m.max_q_norm, rec.q_norm, rec.q_norm_B});
    m.contact_faults = rec.contact_faults;
    if (fc.allFinite()) m.max_contact_force = std::max(m.max_contact_force, fc.norm());
    if (f.allFinite()) {
      m.max_device_force = std::max(m.max_device_force, f.norm());
      m.max_force_jump = std::max(m.max_force_jump, (f - last_f).norm());
      last_f = f;
    }
    if (f.allFinite() && tq.allFinite()) {
      m.peak_stored_energy =
          std::max(m.peak_stored_energy, 0.5 * f.squaredNorm() / c.k_vc + 0.5 * tq.squaredNorm() / c.k_vc_rot);
    }
    if (t > motion_end && t <= motion_end + kWindow) early_p.push_back(p), early_f.push_back(f);
    if (t > hold_end - kWindow && t <= hold_end) late_p.push_back(p), late_f.push_back(f);
  }
  m.cycles = n;
  m.rate_hz = 1e9 / double(period_ns);
  m.coherence_resets = cycle.coherence_resets();
  m.energy_into_hand = device.energy_into_hand();
  if (!std::isfinite(m.energy_into_hand)) m.finite = false;
  m.early_position_rms = RmsAboutTrend(early_p);
  m.late_position_rms = RmsAboutTrend(late_p);
  m.early_force_rms = RmsAboutTrend(early_f);
  m.late_force_rms = RmsAboutTrend(late_f);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& f : late_f) mean += f;
  m.hold_force_mean = late_f.empty() ? 0 : (mean / double(late_f.size())).norm();
  if (!(std::isfinite(m.late_position_rms) && std::isfinite(m.late_force_rms))) m.finite = false;
  m.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return m;
}

}  // namespace contactlab
