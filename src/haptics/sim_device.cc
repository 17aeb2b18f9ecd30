// Simulated 6-DoF haptic device with a mass-spring-damper hand (Barbič & James 2008, sec. 5).
#include "haptics/sim_device.h"

#include <cmath>
#include <string>

#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {

DeviceCapabilities SimDeviceParams::DefaultCapabilities() {
  DeviceCapabilities c;
  c.dof_in = 6;
  c.dof_out = 6;
  c.workspace_min = Eigen::Vector3d(-0.2, -0.2, -0.2);
  c.workspace_max = Eigen::Vector3d(0.2, 0.2, 0.2);
  c.max_force = 8.0;
  c.max_torque = 0.5;
  c.max_stiffness = 3000.0;
  c.max_rot_stiffness = 5.0;
  return c;
}

void SimDeviceParams::Validate(const char* where) const {
  auto positive = [&](double v, const char* name) {
    if (!std::isfinite(v) || v <= 0) Fail(where, std::string(name) + " must be finite and > 0, got " + std::to_string(v));
  };
  positive(handle_mass, "handle_mass");
  positive(handle_inertia, "handle_inertia");
  positive(step_seconds, "step_seconds");
  auto nonneg = [&](double v, const char* name) {
    if (!std::isfinite(v) || v < 0) Fail(where, std::string(name) + " must be finite and >= 0, got " + std::to_string(v));
  };
  nonneg(hand_stiffness, "hand_stiffness");
  nonneg(hand_damping, "hand_damping");
  nonneg(hand_rot_stiffness, "hand_rot_stiffness");
  nonneg(hand_rot_damping, "hand_rot_damping");
}

SimDevice::SimDevice(const SimDeviceParams& params, TargetTrajectory target)
    : params_(params), target_(std::move(target)) {
  params_.Validate("sim device");
  if (!target_) Fail("sim device", "needs a target trajectory");
  X_WD_ = target_(0.0);
}

void SimDevice::AdvanceTo(double t_end) {
  const double h = params_.step_seconds;
  const double m = params_.handle_mass, I = params_.handle_inertia;
  while (t_ + 0.5 * h < t_end) {
    if (zero_requested_.exchange(false, std::memory_order_relaxed)) held_ = Wrench{};
    const double dt = std::min(h, t_end - t_);
    // Hand spring-damper toward the target, plus the device wrench on the handle.
    const Pose X_WT = target_(t_ + dt);
    const Eigen::Vector3d f_hand = params_.hand_stiffness * (X_WT.translation - X_WD_.translation) - params_.hand_damping * v_;
    const Eigen::Vector3d phi = CalcRotationVector(X_WT.rotation * X_WD_.rotation.conjugate());
    const Eigen::Vector3d t_hand = params_.hand_rot_stiffness * phi - params_.hand_rot_damping * w_;
    // Semi-implicit Euler; the passivity observer uses the velocity over the step.
    v_ += (dt / m) * (f_hand + held_.force);
    w_ += (dt / I) * (t_hand + held_.torque);
    energy_ += dt * (held_.force.dot(v_) + held_.torque.dot(w_));
    X_WD_.translation += dt * v_;
    X_WD_.rotation = (RotationFromVector(dt * w_) * X_WD_.rotation).normalized();
    t_ += dt;
  }
}

bool SimDevice::Read(std::int64_t now_ns, DeviceState* out) {
  if (!started_) {
    started_ = true;
    t0_ns_ = now_ns;
  }
  AdvanceTo(1e-9 * double(now_ns - t0_ns_));
  if (silent_) return false;
  out->X_WD = X_WD_;
  out->timestamp_ns = now_ns;
  out->buttons = 0;
  out->sequence = ++sequence_;
  return true;
}

void SimDevice::Write(const Wrench& wrench, std::int64_t, std::uint32_t) {
  held_ = wrench;
  if (zero_requested_.exchange(false, std::memory_order_relaxed)) held_ = Wrench{};
}

}  // namespace contactlab
