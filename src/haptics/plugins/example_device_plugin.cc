// Example ContactLab device plugin (PLUGINS.md): a virtual 6-DoF device whose handle moves on
// a slow circle and which remembers the last wrench written. Copy it to wrap a real SDK
// (OpenHaptics hdGetDoublev / hdSetDoublev, Force Dimension dhdGetPosition / dhdSetForce...).
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>

#include "haptics/device_plugin_abi.h"

namespace {

struct ExampleDevice {
  double radius = 0.02;           // metres, from config "radius=<m>"
  double period_s = 4.0;          // seconds per revolution
  std::int64_t t0_ns = -1;
  std::uint64_t sequence = 0;
  double force[3] = {0, 0, 0};
  double torque[3] = {0, 0, 0};
  std::atomic<bool> zeroed{false};
};

void* Open(const char* config, char* error, size_t error_size) {
  double radius = 0.02;
  if (config != nullptr && config[0] != '\0') {
    if (std::sscanf(config, "radius=%lf", &radius) != 1 || !(radius >= 0 && radius < 1)) {
      std::snprintf(error, error_size, "config '%s' is not 'radius=<metres in [0,1)>'", config);
      return nullptr;
    }
  }
  auto* d = new (std::nothrow) ExampleDevice;
  if (d == nullptr) {
    std::snprintf(error, error_size, "out of memory");
    return nullptr;
  }
  d->radius = radius;
  return d;
}

void Close(void* h) { delete static_cast<ExampleDevice*>(h); }

int GetCapabilities(void*, ContactlabDeviceCaps* caps) {
  std::memset(caps, 0, sizeof(*caps));
  caps->dof_in = 6;
  caps->dof_out = 6;
  for (int i = 0; i < 3; ++i) {
    caps->workspace_min[i] = -0.1;
    caps->workspace_max[i] = 0.1;
  }
  caps->max_force = 5.0;
  caps->max_torque = 0.3;
  caps->max_stiffness = 1500.0;
  caps->max_rot_stiffness = 3.0;
  return 0;
}

int Read(void* h, int64_t now_ns, ContactlabDeviceSample* s) {
  auto* d = static_cast<ExampleDevice*>(h);
  if (d->t0_ns < 0) d->t0_ns = now_ns;
  const double t = 1e-9 * double(now_ns - d->t0_ns);
  const double a = 2 * M_PI * t / d->period_s;
  s->timestamp_ns = now_ns;
  s->position[0] = d->radius * std::cos(a);
  s->position[1] = d->radius * std::sin(a);
  s->position[2] = 0;
  s->quaternion[0] = 1;
  s->quaternion[1] = s->quaternion[2] = s->quaternion[3] = 0;
  s->buttons = 0;
  s->sequence = ++d->sequence;
  return 1;
}

int Write(void* h, const double force[3], const double torque[3], int64_t) {
  auto* d = static_cast<ExampleDevice*>(h);
  const bool zero = d->zeroed.exchange(false);
  for (int i = 0; i < 3; ++i) {
    d->force[i] = zero ? 0 : force[i];
    d->torque[i] = zero ? 0 : torque[i];
  }
  return 0;
}

void EmergencyZero(void* h) { static_cast<ExampleDevice*>(h)->zeroed.store(true); }

const ContactlabDevicePluginV1 kTable = {
    CONTACTLAB_DEVICE_PLUGIN_ABI_VERSION,
    sizeof(ContactlabDevicePluginV1),
    "example-circle",
    &Open,
    &Close,
    &GetCapabilities,
    &Read,
    &Write,
    &EmergencyZero,
};

}  // namespace

extern "C" __attribute__((visibility("default"))) const ContactlabDevicePluginV1* contactlab_device_plugin_v1(void) {
  return &kTable;
}
