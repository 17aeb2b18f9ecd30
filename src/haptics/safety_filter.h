// The last stage before the device (docs/architecture.md "Errors and safety"; Barbič & James
// 2008, sec. 5 saturation): replaces a non-finite wrench by zero, clamps force and torque to the
// device's limits, ramps force in over the first second of a session and after any fault, and
// zeroes output when a watchdog sees the device fall silent or the loop stall.
#pragma once

#include <cstdint>

#include "contact/contact_model.h"

namespace contactlab {

struct SafetyParams {
  double max_force = 0;                 // N, > 0 (usually the device's capability); 0 only without output
  double max_torque = 0;                // N m, >= 0 (0 for a 3-DoF output device)
  bool force_output = true;             // false: an input-only device, every wrench written is zero
  double ramp_seconds = 1.0;            // linear ramp 0 -> 1 at session start and after faults
  double device_timeout_seconds = 0.05; // no new device sample for longer -> zero output
  double loop_stall_seconds = 0.01;     // gap between two cycles longer than this -> zero output

  // Throws Error naming WHERE and the field when a value is non-finite or out of range.
  void Validate(const char* where) const;
};

struct DeviceCapabilities;

// The safety limits for a device with CAPS: a limit <= 0 in S means "the device's own". An
// input-only device (dof_out 0) gets force_output = false and zero limits, which Validate
// accepts: such a device (a SpaceMouse) runs a session that displays no force.
SafetyParams ResolveSafetyLimits(SafetyParams s, const DeviceCapabilities& caps);

// Counters: every intervention is counted (read them after the loop, or copy them per cycle).
struct SafetyStats {
  std::int64_t cycles = 0;
  std::int64_t non_finite = 0;        // wrenches replaced by zero
  std::int64_t force_clamped = 0;
  std::int64_t torque_clamped = 0;
  std::int64_t device_silent = 0;     // cycles zeroed by the device watchdog
  std::int64_t loop_stalls = 0;       // stalls detected (each zeroes one cycle)
  std::int64_t faults = 0;            // fault onsets (each restarts the ramp)
};

// Why this cycle's output differs from the input (bit flags).
enum SafetyFlag : std::uint32_t {
  kSafetyNone = 0,
  kSafetyNonFinite = 1u << 0,
  kSafetyForceClamped = 1u << 1,
  kSafetyTorqueClamped = 1u << 2,
  kSafetyDeviceSilent = 1u << 3,
  kSafetyLoopStall = 1u << 4,
  kSafetyRamping = 1u << 5,
};

class SafetyFilter {
 public:
  // Throws Error when PARAMS is invalid.
  explicit SafetyFilter(const SafetyParams& params);

  // Starts a session at NOW_NS (the loop clock): the ramp restarts from zero.
  void Start(std::int64_t now_ns);

  // Filters one cycle's wrench. NOW_NS: the loop clock; LAST_SAMPLE_NS: loop-clock time at
  // which the device last delivered a new sample. Returns the wrench to write; *FLAGS (if not
  // null) gets the SafetyFlag bits. Allocation-free, lock-free, never throws.
  Wrench Filter(const Wrench& in, std::int64_t now_ns, std::int64_t last_sample_ns, std::uint32_t* flags = nullptr);

  // Current ramp factor in [0, 1] at NOW_NS.
  double RampFactor(std::int64_t now_ns) const;

  const SafetyStats& stats() const { return stats_; }
  const SafetyParams& params() const { return params_; }

 private:
  void MarkFault(std::int64_t now_ns);

  SafetyParams params_;
  SafetyStats stats_;
  std::int64_t ramp_start_ns_ = 0;
  std::int64_t last_cycle_ns_ = 0;
  bool started_ = false;
  bool in_fault_ = false;
};

}  // namespace contactlab
