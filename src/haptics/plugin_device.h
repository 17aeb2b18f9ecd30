// A haptic device provided by a shared-library plugin through the C ABI of device_plugin_abi.h
// (PLUGINS.md), loaded with dlopen: how a lab wraps OpenHaptics or the Force Dimension SDK for
// the haptic loop (Barbič & James 2008, sec. 5).
#pragma once

#include <filesystem>
#include <string>

#include "haptics/device_plugin_abi.h"
#include "haptics/haptic_device.h"

namespace contactlab {

class PluginDevice final : public HapticDevice {
 public:
  // Loads LIBRARY (a path; a name without a folder is in the working folder, never searched on
  // the library path), looks up contactlab_device_plugin_v1, checks the ABI version and table
  // size, and opens the device with CONFIG. Throws Error naming the library and what failed (not
  // found, not a regular file: a named pipe, folder or device is refused without blocking;
  // dlopen message, missing symbol, wrong ABI version, null function pointer, open refused).
  PluginDevice(const std::filesystem::path& library, const std::string& config);
  ~PluginDevice() override;  // closes the device, then dlclose
  PluginDevice(const PluginDevice&) = delete;
  PluginDevice& operator=(const PluginDevice&) = delete;

  std::string_view name() const override { return name_; }
  DeviceCapabilities capabilities() const override { return capabilities_; }
  bool Read(std::int64_t now_ns, DeviceState* out) override;
  void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) override;
  void EmergencyZero() noexcept override;

  std::int64_t read_errors() const { return read_errors_; }
  std::int64_t write_errors() const { return write_errors_; }

 private:
  void* library_ = nullptr;
  const ContactlabDevicePluginV1* api_ = nullptr;
  void* handle_ = nullptr;
  std::string name_;
  DeviceCapabilities capabilities_;
  DeviceState last_;
  std::int64_t read_errors_ = 0;
  std::int64_t write_errors_ = 0;
};

}  // namespace contactlab
