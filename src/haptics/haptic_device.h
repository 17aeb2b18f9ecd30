// The one interface every haptic device backend implements (Barbič & James 2008, sec. 5: the
// manipulandum pose goes in, the coupling wrench comes out): sim, replay, udp, spacenav and
// dlopen'ed plugins.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "contact/contact_model.h"
#include "geometry/pose.h"

namespace contactlab {

// What a device can do. Limits are the device's own; the safety filter clamps to them.
struct DeviceCapabilities {
  int dof_in = 6;                    // pose degrees of freedom read (3 or 6)
  int dof_out = 6;                   // wrench degrees of freedom written (0 input-only, 3, 6)
  Eigen::Vector3d workspace_min = Eigen::Vector3d::Constant(-0.1);  // workspace box, metres
  Eigen::Vector3d workspace_max = Eigen::Vector3d::Constant(0.1);
  double max_force = 0;              // N (0 when dof_out == 0)
  double max_torque = 0;             // N m
  double max_stiffness = 0;          // largest stable translational stiffness, N/m
  double max_rot_stiffness = 0;      // N m / rad
};

// An input-only device (dof_out 0, e.g. a SpaceMouse): CAPS with no force output. The haptic
// cycle then writes zero wrenches and the safety filter accepts the zero force limits.
inline DeviceCapabilities InputOnlyCapabilities(DeviceCapabilities caps) {
  caps.dof_out = 0;
  caps.max_force = caps.max_torque = 0;
  caps.max_stiffness = caps.max_rot_stiffness = 0;
  return caps;
}

// Counters of a device that receives samples it may reject (udp); all zero for devices that
// cannot reject a sample. Plain integers, so a CycleRecord can carry a copy each cycle.
struct DeviceInputStats {
  std::int64_t received = 0;      // datagrams or samples received
  std::int64_t accepted = 0;
  std::int64_t malformed = 0;     // bad length, header, checksum or a non-finite value
  std::int64_t duplicate = 0;
  std::int64_t out_of_order = 0;
  std::int64_t stale = 0;         // too old
  std::int64_t future = 0;        // timestamp ahead of what the local clock allows
  std::int64_t resyncs = 0;       // stream restarts accepted (after a silence or a sender restart)
  std::int64_t foreign = 0;       // from a sender not allowed (udp: not loopback, or not a --device-peer)
  std::uint32_t last_foreign_address = 0;  // the latest such sender's IPv4 address (host order)
  std::int64_t rejected() const { return malformed + duplicate + out_of_order + stale + future + foreign; }
};

// One pose sample. Timestamps are nanoseconds on the device's clock (see each backend).
struct DeviceState {
  Pose X_WD;                         // manipulandum pose in world (device frame = world)
  std::int64_t timestamp_ns = 0;     // when the pose was sampled
  std::uint32_t buttons = 0;         // bit i = button i pressed
  std::uint64_t sequence = 0;        // increases with each new sample
};

// Whether a device may act on a sampled pose (POSITION x, y, z; QUATERNION w, x, y, z, not
// necessarily unit): every number finite, and the quaternion's squared norm finite and above
// 1e-12, so that it normalises to a unit quaternion (a squared norm that overflows, components
// beyond about 1e154, would normalise to zero). Every device that takes poses from outside the
// process (UDP packets, plugins) refuses the others.
inline bool IsUsableDevicePose(const double* position, const double* quaternion) {
  bool finite = true;
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(position[i]);
  double squared_norm = 0;
  for (int i = 0; i < 4; ++i) {
    finite = finite && std::isfinite(quaternion[i]);
    squared_norm += quaternion[i] * quaternion[i];
  }
  return finite && squared_norm > 1e-12 && std::isfinite(squared_norm);
}

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  virtual std::string_view name() const = 0;
  virtual DeviceCapabilities capabilities() const = 0;

  // Reads the newest sample into *OUT. NOW_NS is the haptic loop's clock (CLOCK_MONOTONIC or
  // simulated time); simulated devices advance to it, real ones may ignore it. Returns false
  // when no new sample has arrived since the last call (*OUT then holds the previous one).
  // Called only from the haptic loop thread; allocation-free; never throws.
  virtual bool Read(std::int64_t now_ns, DeviceState* out) = 0;

  // Sends WRENCH (force N, torque N m, world frame, about the manipulandum origin) to be held
  // until the next Write. SAFETY_FLAGS: the cycle's SafetyFlag bits (safety_filter.h), for
  // devices whose protocol carries them. Called only from the haptic loop thread; never throws.
  virtual void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) = 0;

  // Zeroes output at once; safe to call from any thread (watchdog, signal-driven stop).
  virtual void EmergencyZero() noexcept = 0;

  // Rejection counters of the device's input stream (see DeviceInputStats). Called from the
  // haptic loop thread; allocation-free; never throws.
  virtual DeviceInputStats input_stats() const { return {}; }

  // One line for the user: the kind and, where it matters, how to reach it (a udp device's
  // bound port). Not for the haptic loop (it may allocate).
  virtual std::string description() const { return std::string(name()); }
};

}  // namespace contactlab
