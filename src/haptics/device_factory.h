// Makes a haptic device from a short text spec (for the `contactlab session` command and the
// timing tools; Barbič & James 2008, sec. 5 runs against any 6-DoF device).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "haptics/haptic_device.h"

namespace contactlab {

// SPEC forms:
//   sim                          simulated device, hand holding still at the origin
//   sim:circle[:RADIUS[:PERIOD]] hand target on a circle in the xy plane (m, s)
//   replay:FILE.csv              recorded trajectory (t,x,y,z,qw,qx,qy,qz)
//   udp:LISTEN_PORT[:PEER_PORT]  UDP device on 127.0.0.1 (UDP_PROTOCOL.md)
//   udp:ADDRESS:LISTEN_PORT[:PEER_PORT]
//                                UDP device bound to IPv4 ADDRESS (0.0.0.0: all interfaces), an
//                                explicit opt-in: OPTIONS.peers must list the senders to accept
//   spacenav                     3Dconnexion mouse via libspnav (input only; if built)
//   plugin:LIBRARY.so[?CONFIG]   dlopen'ed plugin (PLUGINS.md)
// Throws Error naming the spec and what is wrong (unknown kind, bad number, and whatever the
// backend throws: missing file, port in use, no spacenavd, plugin refused).
struct DeviceOptions {
  std::vector<std::string> peers;  // udp: IPv4 addresses of the senders accepted (--device-peer)
};
std::unique_ptr<HapticDevice> MakeDevice(const std::string& spec, const DeviceOptions& options = {});

// True when the spacenav backend was compiled in.
bool SpacenavAvailable();

}  // namespace contactlab
