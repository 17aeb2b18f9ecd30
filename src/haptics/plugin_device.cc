// A haptic device loaded from a plugin shared library (PLUGINS.md).
#include "haptics/plugin_device.h"

#include <dlfcn.h>

#include <cmath>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/input_files.h"

namespace contactlab {

PluginDevice::PluginDevice(const std::filesystem::path& library, const std::string& config) {
  const std::string where = "device plugin " + library.string();
  // The library is a file, checked before dlopen, which would block forever reading a named
  // pipe and misname a folder or a device. A name without a folder is the working folder's
  // file, as for every other input (dlopen would search the library path for it instead).
  const std::filesystem::path file = library.has_parent_path() ? library : std::filesystem::path(".") / library;
  CheckInputFile(file, "device plugin library");
  RecordInputFile(file);  // an input like any other: no output of the session may replace it
  library_ = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library_ == nullptr) {
    const char* e = dlerror();
    Fail(where, std::string("dlopen failed: ") + (e ? e : "unknown error"));
  }
  // From here on, failures must release the library.
  auto fail = [&](const std::string& what) {
    if (handle_ != nullptr && api_ != nullptr) api_->close(handle_);
    dlclose(library_);
    library_ = nullptr;
    Fail(where, what);
  };
  void* sym = dlsym(library_, CONTACTLAB_DEVICE_PLUGIN_SYMBOL);
  if (sym == nullptr) fail("does not export " CONTACTLAB_DEVICE_PLUGIN_SYMBOL);
  const auto entry = reinterpret_cast<ContactlabDevicePluginEntryV1>(sym);
  api_ = entry();
  if (api_ == nullptr) fail(CONTACTLAB_DEVICE_PLUGIN_SYMBOL "() returned null");
  if (api_->abi_version != CONTACTLAB_DEVICE_PLUGIN_ABI_VERSION)
    fail("ABI version " + std::to_string(api_->abi_version) + ", expected " +
         std::to_string(CONTACTLAB_DEVICE_PLUGIN_ABI_VERSION));
  if (api_->struct_size < sizeof(ContactlabDevicePluginV1))
    fail("function table is " + std::to_string(api_->struct_size) + " bytes, expected " +
         std::to_string(sizeof(ContactlabDevicePluginV1)));
  if (!api_->open || !api_->close || !api_->get_capabilities || !api_->read || !api_->write || !api_->emergency_zero)
    fail("function table has a null entry");
  name_ = api_->name != nullptr ? api_->name : "plugin";

  // Open the device and read its capabilities.
  char error[512] = {0};
  handle_ = api_->open(config.c_str(), error, sizeof(error));
  if (handle_ == nullptr) {
    error[sizeof(error) - 1] = '\0';
    fail(std::string("open(\"") + config + "\") refused: " + (error[0] ? error : "no reason given"));
  }
  ContactlabDeviceCaps caps{};
  if (api_->get_capabilities(handle_, &caps) != 0) fail("get_capabilities failed");
  capabilities_.dof_in = caps.dof_in;
  capabilities_.dof_out = caps.dof_out;
  capabilities_.workspace_min = Eigen::Vector3d(caps.workspace_min[0], caps.workspace_min[1], caps.workspace_min[2]);
  capabilities_.workspace_max = Eigen::Vector3d(caps.workspace_max[0], caps.workspace_max[1], caps.workspace_max[2]);
  capabilities_.max_force = caps.max_force;
  capabilities_.max_torque = caps.max_torque;
  capabilities_.max_stiffness = caps.max_stiffness;
  capabilities_.max_rot_stiffness = caps.max_rot_stiffness;
  if (!std::isfinite(caps.max_force) || caps.max_force < 0 || !std::isfinite(caps.max_torque) || caps.max_torque < 0)
    fail("capabilities report a negative or non-finite force or torque limit");
}

PluginDevice::~PluginDevice() {
  if (handle_ != nullptr) api_->close(handle_);
  if (library_ != nullptr) dlclose(library_);
}

bool PluginDevice::Read(std::int64_t now_ns, DeviceState* out) {
  ContactlabDeviceSample s{};
  const int r = api_->read(handle_, now_ns, &s);
  if (r < 0) ++read_errors_;
  if (r == 1) {
    if (IsUsableDevicePose(s.position, s.quaternion)) {
      const Eigen::Quaterniond q(s.quaternion[0], s.quaternion[1], s.quaternion[2], s.quaternion[3]);
      last_.X_WD = Pose{q.normalized(), Eigen::Vector3d(s.position[0], s.position[1], s.position[2])};
      last_.timestamp_ns = s.timestamp_ns;
      last_.buttons = s.buttons;
      last_.sequence = s.sequence;
      *out = last_;
      return true;
    }
    ++read_errors_;  // a malformed sample is not acted on
  }
  *out = last_;
  return false;
}

void PluginDevice::Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t) {
  const double f[3] = {wrench.force.x(), wrench.force.y(), wrench.force.z()};
  const double t[3] = {wrench.torque.x(), wrench.torque.y(), wrench.torque.z()};
  if (api_->write(handle_, f, t, now_ns) != 0) ++write_errors_;
}

void PluginDevice::EmergencyZero() noexcept { api_->emergency_zero(handle_); }

}  // namespace contactlab
