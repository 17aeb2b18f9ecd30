// Places a device's workspace in the scene: the device frame D0 sits at pose X_WD0 in the
// world, so a manipulandum pose X_D0M read from the device is X_WM = X_WD0 * X_D0M, and a
// world wrench about the manipulandum origin is rotated back into the device frame. Lets a
// scene put its haptic body anywhere while the device stays centred in its own workspace.
#pragma once

#include "haptics/haptic_device.h"

namespace contactlab {

class WorkspaceMappedDevice final : public HapticDevice {
 public:
  // INNER must outlive this object.
  WorkspaceMappedDevice(HapticDevice& inner, const Pose& X_WD0) : inner_(inner), X_WD0_(X_WD0) {}

  std::string_view name() const override { return inner_.name(); }
  DeviceCapabilities capabilities() const override {
    DeviceCapabilities c = inner_.capabilities();
    c.workspace_min += X_WD0_.translation;  // axis-aligned approximation for rotated mappings
    c.workspace_max += X_WD0_.translation;
    return c;
  }
  bool Read(std::int64_t now_ns, DeviceState* out) override {
    DeviceState s;
    const bool fresh = inner_.Read(now_ns, &s);
    *out = s;
    out->X_WD = X_WD0_ * s.X_WD;
    return fresh;
  }
  void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) override {
    const Eigen::Matrix3d R_D0W = X_WD0_.R().transpose();
    Wrench w;
    w.force = R_D0W * wrench.force;
    w.torque = R_D0W * wrench.torque;
    inner_.Write(w, now_ns, safety_flags);
  }
  void EmergencyZero() noexcept override { inner_.EmergencyZero(); }
  DeviceInputStats input_stats() const override { return inner_.input_stats(); }
  std::string description() const override { return inner_.description(); }
  HapticDevice& inner() { return inner_; }

 private:
  HapticDevice& inner_;
  Pose X_WD0_;
};

}  // namespace contactlab
