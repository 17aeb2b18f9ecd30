// A 3Dconnexion SpaceMouse as an input-only 6-DoF device through libspnav (needs spacenavd):
// its deflections are integrated as velocities into a manipulandum pose (Barbič & James 2008,
// sec. 5 needs only the manipulandum pose; no force is displayed). Built when libspnav is found.
#pragma once

#include "haptics/haptic_device.h"

namespace contactlab {

struct SpacenavParams {
  double translation_speed = 0.1 / 350;  // m/s per device unit (full deflection ~350 -> 0.1 m/s)
  double rotation_speed = 1.0 / 350;     // rad/s per device unit
  Pose X_W0;                             // initial pose
  DeviceCapabilities capabilities;       // dof_out is forced to 0
};

class SpacenavDevice final : public HapticDevice {
 public:
  // Connects to spacenavd. Throws Error with a clear message when the daemon or device is
  // absent (spnav_open fails).
  explicit SpacenavDevice(const SpacenavParams& params);
  ~SpacenavDevice() override;
  SpacenavDevice(const SpacenavDevice&) = delete;
  SpacenavDevice& operator=(const SpacenavDevice&) = delete;

  // What a SpaceMouse reports given the configured CAPS: 6-DoF input, no force output (dof_out
  // 0, zero limits), which the session's safety filter accepts as "display nothing".
  static DeviceCapabilities Capabilities(const DeviceCapabilities& caps) {
    DeviceCapabilities c = InputOnlyCapabilities(caps);
    c.dof_in = 6;
    return c;
  }

  std::string_view name() const override { return "spacenav"; }
  DeviceCapabilities capabilities() const override { return params_.capabilities; }
  bool Read(std::int64_t now_ns, DeviceState* out) override;
  void Write(const Wrench&, std::int64_t, std::uint32_t) override {}  // input only
  void EmergencyZero() noexcept override {}

 private:
  SpacenavParams params_;
  Pose X_WD_;
  double motion_[6] = {0, 0, 0, 0, 0, 0};
  std::uint32_t buttons_ = 0;
  std::int64_t last_ns_ = -1;
  std::uint64_t sequence_ = 0;
};

}  // namespace contactlab
