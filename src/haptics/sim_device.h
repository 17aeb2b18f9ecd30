// A simulated 6-DoF haptic device for closed-loop tests of the haptic display (Barbič & James
// 2008, sec. 5): a handle mass pulled by a spring-damper "hand" toward a target trajectory,
// with the device's output wrench acting on the handle.
#pragma once

#include <atomic>
#include <functional>

#include "haptics/haptic_device.h"

namespace contactlab {

// The hand's target pose as a function of time in seconds since the device started.
using TargetTrajectory = std::function<Pose(double t_seconds)>;

struct SimDeviceParams {
  double handle_mass = 0.15;       // kg
  double handle_inertia = 2e-4;    // kg m^2 (isotropic)
  double hand_stiffness = 400;     // N/m, hand spring pulling the handle toward the target
  double hand_damping = 6;         // N s/m, on the handle's absolute velocity
  double hand_rot_stiffness = 1.5; // N m / rad
  double hand_rot_damping = 0.02;  // N m s / rad
  double step_seconds = 1e-4;      // internal integration step (semi-implicit Euler)
  DeviceCapabilities capabilities = DefaultCapabilities();

  static DeviceCapabilities DefaultCapabilities();
  // Throws Error naming WHERE and the field when a value is non-finite or out of range.
  void Validate(const char* where) const;
};

// Read(now) integrates the handle up to NOW (zero-order hold of the last written wrench) and
// returns its pose, timestamped NOW. The passivity observer energy_into_hand() accumulates
// the work the device wrench does on the handle, ∫ (F·v + T·ω) dt.
class SimDevice final : public HapticDevice {
 public:
  // Throws Error when PARAMS is invalid or TARGET is empty.
  SimDevice(const SimDeviceParams& params, TargetTrajectory target);

  std::string_view name() const override { return "sim"; }
  DeviceCapabilities capabilities() const override { return params_.capabilities; }
  bool Read(std::int64_t now_ns, DeviceState* out) override;
  void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) override;
  void EmergencyZero() noexcept override { zero_requested_.store(true, std::memory_order_relaxed); }

  // Test hooks: while silent, Read returns false (a stalled device); the handle still moves.
  void SetSilent(bool silent) { silent_ = silent; }

  const Pose& handle_pose() const { return X_WD_; }
  const Eigen::Vector3d& handle_velocity() const { return v_; }
  const Eigen::Vector3d& handle_angular_velocity() const { return w_; }
  const Wrench& held_wrench() const { return held_; }
  double energy_into_hand() const { return energy_; }
  double time_seconds() const { return t_; }

 private:
  void AdvanceTo(double t);

  SimDeviceParams params_;
  TargetTrajectory target_;
  bool started_ = false;
  bool silent_ = false;
  std::int64_t t0_ns_ = 0;
  double t_ = 0;
  Pose X_WD_;
  Eigen::Vector3d v_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_ = Eigen::Vector3d::Zero();
  Wrench held_;
  double energy_ = 0;
  std::uint64_t sequence_ = 0;
  std::atomic<bool> zero_requested_{false};
};

}  // namespace contactlab
