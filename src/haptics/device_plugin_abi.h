/* The C ABI of ContactLab device plugins (see PLUGINS.md): a shared library exports
 * `contactlab_device_plugin_v1`, returning a table of function pointers through which the
 * haptic loop (Barbič & James 2008, sec. 5) reads the manipulandum pose and writes the wrench.
 * Plain C so that a lab can wrap OpenHaptics, the Force Dimension SDK, or anything else. */
#ifndef CONTACTLAB_HAPTICS_DEVICE_PLUGIN_ABI_H_
#define CONTACTLAB_HAPTICS_DEVICE_PLUGIN_ABI_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define CONTACTLAB_DEVICE_PLUGIN_ABI_VERSION 1u
#define CONTACTLAB_DEVICE_PLUGIN_SYMBOL "contactlab_device_plugin_v1"

/* Device limits; SI units. */
typedef struct ContactlabDeviceCaps {
  int32_t dof_in;             /* 3 or 6 */
  int32_t dof_out;            /* 0 (input only), 3 or 6 */
  double workspace_min[3];    /* metres */
  double workspace_max[3];
  double max_force;           /* N */
  double max_torque;          /* N m */
  double max_stiffness;       /* N/m */
  double max_rot_stiffness;   /* N m / rad */
} ContactlabDeviceCaps;

/* One pose sample. */
typedef struct ContactlabDeviceSample {
  int64_t timestamp_ns;       /* plugin's clock */
  double position[3];         /* metres */
  double quaternion[4];       /* w, x, y, z; need not be normalised, must be non-zero */
  uint32_t buttons;           /* bit i = button i */
  uint64_t sequence;          /* increases with each new sample */
} ContactlabDeviceSample;

typedef struct ContactlabDevicePluginV1 {
  uint32_t abi_version;       /* CONTACTLAB_DEVICE_PLUGIN_ABI_VERSION */
  uint32_t struct_size;       /* sizeof(ContactlabDevicePluginV1) */
  const char* name;           /* short device name, static storage */

  /* Opens the device with a free-form CONFIG string (may be ""). Returns an opaque handle, or
   * NULL after writing a NUL-terminated reason into ERROR (capacity ERROR_SIZE). */
  void* (*open)(const char* config, char* error, size_t error_size);
  /* Closes the device; the handle is not used afterwards. Must leave the device at zero force. */
  void (*close)(void* handle);
  /* Fills *CAPS; returns 0 on success. */
  int (*get_capabilities)(void* handle, ContactlabDeviceCaps* caps);
  /* Haptic thread, every cycle: fills *SAMPLE with the newest pose; returns 1 when it is new,
   * 0 when nothing new arrived, negative on a device error. Must not block or allocate. */
  int (*read)(void* handle, int64_t now_ns, ContactlabDeviceSample* sample);
  /* Haptic thread, every cycle: holds FORCE[3] (N) and TORQUE[3] (N m) until the next call;
   * returns 0 on success. Must not block or allocate. */
  int (*write)(void* handle, const double force[3], const double torque[3], int64_t now_ns);
  /* Any thread, any time: zero output at once. Must be thread-safe. */
  void (*emergency_zero)(void* handle);
} ContactlabDevicePluginV1;

/* The one exported symbol. */
typedef const ContactlabDevicePluginV1* (*ContactlabDevicePluginEntryV1)(void);

#ifdef __cplusplus
}
#endif

#endif /* CONTACTLAB_HAPTICS_DEVICE_PLUGIN_ABI_H_ */
