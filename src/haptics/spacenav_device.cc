// 3Dconnexion SpaceMouse through libspnav, input only.
#include "haptics/spacenav_device.h"

#include <spnav.h>

#include "util/error.h"

namespace contactlab {

SpacenavDevice::SpacenavDevice(const SpacenavParams& params) : params_(params), X_WD_(params.X_W0) {
  params_.capabilities = Capabilities(params_.capabilities);
  if (spnav_open() == -1)
    Fail("spacenav device",
         "cannot connect to spacenavd (libspnav spnav_open failed): is the spacenavd daemon running and a "
         "3Dconnexion device plugged in?");
}

SpacenavDevice::~SpacenavDevice() { spnav_close(); }

bool SpacenavDevice::Read(std::int64_t now_ns, DeviceState* out) {
  // Drain events: motion sets the current deflection, buttons toggle bits.
  spnav_event ev;
  while (spnav_poll_event(&ev) > 0) {
    if (ev.type == SPNAV_EVENT_MOTION) {
      motion_[0] = ev.motion.x, motion_[1] = ev.motion.y, motion_[2] = ev.motion.z;
      motion_[3] = ev.motion.rx, motion_[4] = ev.motion.ry, motion_[5] = ev.motion.rz;
    } else if (ev.type == SPNAV_EVENT_BUTTON && ev.button.bnum >= 0 && ev.button.bnum < 32) {
      const std::uint32_t bit = 1u << ev.button.bnum;
      buttons_ = ev.button.press ? (buttons_ | bit) : (buttons_ & ~bit);
    }
  }
  // Integrate the deflection as a velocity since the previous Read.
  if (last_ns_ >= 0) {
    const double dt = 1e-9 * double(now_ns - last_ns_);
    const Eigen::Vector3d v(motion_[0], motion_[1], motion_[2]);
    const Eigen::Vector3d w(motion_[3], motion_[4], motion_[5]);
    X_WD_.translation += dt * params_.translation_speed * v;
    X_WD_.rotation = (RotationFromVector(dt * params_.rotation_speed * w) * X_WD_.rotation).normalized();
  }
  last_ns_ = now_ns;
  out->X_WD = X_WD_;
  out->timestamp_ns = now_ns;
  out->buttons = buttons_;
  out->sequence = ++sequence_;
  return true;
}

}  // namespace contactlab
