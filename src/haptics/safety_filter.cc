// Safety filter before the device (docs/architecture.md "Errors and safety").
#include "haptics/safety_filter.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "haptics/haptic_device.h"
#include "util/error.h"

namespace contactlab {

void SafetyParams::Validate(const char* where) const {
  auto check = [&](double v, bool ok, const char* name, const char* rule) {
    if (!std::isfinite(v) || !ok) Fail(where, std::string(name) + " must be " + rule + ", got " + std::to_string(v));
  };
  if (force_output) {
    check(max_force, max_force > 0, "max_force", "finite and > 0 (0 only for an input-only device)");
  } else {
    check(max_force, max_force >= 0, "max_force", "finite and >= 0");
  }
  check(max_torque, max_torque >= 0, "max_torque", "finite and >= 0");
  check(ramp_seconds, ramp_seconds >= 0, "ramp_seconds", "finite and >= 0");
  check(device_timeout_seconds, device_timeout_seconds > 0, "device_timeout_seconds", "finite and > 0");
  check(loop_stall_seconds, loop_stall_seconds > 0, "loop_stall_seconds", "finite and > 0");
}

SafetyParams ResolveSafetyLimits(SafetyParams s, const DeviceCapabilities& caps) {
  if (caps.dof_out == 0) {
    s.force_output = false;
    s.max_force = s.max_torque = 0;
    return s;
  }
  if (s.max_force <= 0) s.max_force = caps.max_force;
  if (s.max_torque <= 0) s.max_torque = caps.max_torque;
  return s;
}

SafetyFilter::SafetyFilter(const SafetyParams& params) : params_(params) { params_.Validate("safety parameters"); }

void SafetyFilter::Start(std::int64_t now_ns) {
  started_ = true;
  in_fault_ = false;
  ramp_start_ns_ = now_ns;
  last_cycle_ns_ = now_ns;
}

void SafetyFilter::MarkFault(std::int64_t now_ns) {
  if (!in_fault_) ++stats_.faults;
  in_fault_ = true;
  ramp_start_ns_ = now_ns;  // the ramp restarts once the fault clears
}

double SafetyFilter::RampFactor(std::int64_t now_ns) const {
  if (params_.ramp_seconds <= 0) return 1.0;
  const double t = 1e-9 * double(now_ns - ramp_start_ns_) / params_.ramp_seconds;
  return std::clamp(t, 0.0, 1.0);
}

Wrench SafetyFilter::Filter(const Wrench& in, std::int64_t now_ns, std::int64_t last_sample_ns, std::uint32_t* flags) {
  std::uint32_t f = kSafetyNone;
  if (!started_) Start(now_ns);
  ++stats_.cycles;
  Wrench out = in;
  bool fault = false;

  // Watchdogs: a stalled loop (gap since the previous cycle) or a silent device.
  const double gap = 1e-9 * double(now_ns - last_cycle_ns_);
  last_cycle_ns_ = now_ns;
  if (gap > params_.loop_stall_seconds) {
    ++stats_.loop_stalls;
    f |= kSafetyLoopStall;
    fault = true;
  }
  if (1e-9 * double(now_ns - last_sample_ns) > params_.device_timeout_seconds) {
    ++stats_.device_silent;
    f |= kSafetyDeviceSilent;
    fault = true;
  }

  // A non-finite wrench is replaced by zero (and counts as a fault: the ramp restarts).
  if (!out.force.allFinite() || !out.torque.allFinite()) {
    ++stats_.non_finite;
    f |= kSafetyNonFinite;
    fault = true;
  }

  if (fault) {
    MarkFault(now_ns);
    out.force.setZero();
    out.torque.setZero();
  } else if (!params_.force_output) {
    in_fault_ = false;
    out.force.setZero();  // an input-only device: nothing to display, nothing clamped
    out.torque.setZero();
  } else {
    in_fault_ = false;
    // Clamp force and torque magnitudes to the device's limits (direction kept).
    const double fn = out.force.norm();
    if (fn > params_.max_force) {
      out.force *= params_.max_force / fn;
      ++stats_.force_clamped;
      f |= kSafetyForceClamped;
    }
    const double tn = out.torque.norm();
    if (tn > params_.max_torque) {
      if (params_.max_torque > 0) {
        out.torque *= params_.max_torque / tn;
      } else {
        out.torque.setZero();
      }
      ++stats_.torque_clamped;
      f |= kSafetyTorqueClamped;
    }
    // Ramp in after session start and after any fault.
    const double s = RampFactor(now_ns);
    if (s < 1.0) {
      out.force *= s;
      out.torque *= s;
      f |= kSafetyRamping;
    }
  }
  if (flags != nullptr) *flags = f;
  return out;
}

}  // namespace contactlab
