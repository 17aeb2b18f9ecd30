// A device plugin for tests (PLUGINS.md): every read returns the same sample, at the origin with
// the quaternion its config gives ("w,x,y,z", not normalised), so that a test can hand the
// plugin device the samples a faulty or hostile plugin could.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>

#include "haptics/device_plugin_abi.h"

namespace {

struct FixedDevice {
  double quaternion[4] = {1, 0, 0, 0};
  std::uint64_t sequence = 0;
};

void* Open(const char* config, char* error, size_t error_size) {
  auto* d = new (std::nothrow) FixedDevice;
  if (d == nullptr) return nullptr;
  double* q = d->quaternion;
  if (config == nullptr || std::sscanf(config, "%lf,%lf,%lf,%lf", &q[0], &q[1], &q[2], &q[3]) != 4) {
    std::snprintf(error, error_size, "config '%s' is not 'w,x,y,z'", config == nullptr ? "" : config);
    delete d;
    return nullptr;
  }
  return d;
}

void Close(void* h) { delete static_cast<FixedDevice*>(h); }

int GetCapabilities(void*, ContactlabDeviceCaps* caps) {
  std::memset(caps, 0, sizeof(*caps));
  caps->dof_in = 6;
  caps->dof_out = 6;
  for (int i = 0; i < 3; ++i) caps->workspace_min[i] = -0.1, caps->workspace_max[i] = 0.1;
  caps->max_force = 5.0;
  caps->max_torque = 0.3;
  return 0;
}

int Read(void* h, int64_t now_ns, ContactlabDeviceSample* s) {
  auto* d = static_cast<FixedDevice*>(h);
  std::memset(s, 0, sizeof(*s));
  s->timestamp_ns = now_ns;
  for (int i = 0; i < 4; ++i) s->quaternion[i] = d->quaternion[i];
  s->sequence = ++d->sequence;
  return 1;
}

int Write(void*, const double*, const double*, int64_t) { return 0; }
void EmergencyZero(void*) {}

const ContactlabDevicePluginV1 kTable = {
    CONTACTLAB_DEVICE_PLUGIN_ABI_VERSION,
    sizeof(ContactlabDevicePluginV1),
    "fixed-sample",
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
