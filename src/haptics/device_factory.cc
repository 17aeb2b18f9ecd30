// Haptic device factory (sim, replay, udp, spacenav, plugin).
#include "haptics/device_factory.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "haptics/plugin_device.h"
#include "haptics/replay_device.h"
#include "haptics/sim_device.h"
#include "haptics/udp_device.h"
#include "util/error.h"
#ifdef CONTACTLAB_HAVE_SPNAV
#include "haptics/spacenav_device.h"
#endif

namespace contactlab {
namespace {

std::vector<std::string> Split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = s.find(sep, start);
    out.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return out;
    start = at + 1;
  }
}

double ParseNumber(const std::string& text, const std::string& spec, const char* what) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::logic_error&) {
  }
  Fail("device spec '" + spec + "'", std::string(what) + " '" + text + "' is not a number");
}

// A port is written in decimal digits: "1e3" or "0x50" or "80.0" are not ports, though they
// spell numbers.
std::uint16_t ParsePort(const std::string& text, const std::string& spec) {
  const bool digits = !text.empty() && text.size() <= 5 &&
                      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  const long v = digits ? std::stol(text) : -1;
  if (v < 0 || v > 65535)
    Fail("device spec '" + spec + "'", "port '" + QuoteToken(text) + "' is not in 0..65535 (decimal digits)");
  return std::uint16_t(v);
}

}  // namespace

bool SpacenavAvailable() {
#ifdef CONTACTLAB_HAVE_SPNAV
  return true;
#else
  return false;
#endif
}

std::unique_ptr<HapticDevice> MakeDevice(const std::string& spec, const DeviceOptions& options) {
  const std::size_t colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  const std::string where = "device spec '" + spec + "'";

  if (kind != "udp" && !options.peers.empty()) Fail("--device-peer", "applies to udp devices only, not '" + spec + "'");
  if (kind == "sim") {
    const std::vector<std::string> f = rest.empty() ? std::vector<std::string>{} : Split(rest, ':');
    if (f.empty()) return std::make_unique<SimDevice>(SimDeviceParams{}, [](double) { return Pose{}; });
    if (f[0] != "circle" || f.size() > 3) Fail(where, "expected sim or sim:circle[:RADIUS[:PERIOD]]");
    const double r = f.size() > 1 ? ParseNumber(f[1], spec, "radius") : 0.03;
    const double T = f.size() > 2 ? ParseNumber(f[2], spec, "period") : 4.0;
    if (!(r >= 0 && T > 0)) Fail(where, "radius must be >= 0 and period > 0");
    return std::make_unique<SimDevice>(SimDeviceParams{}, [r, T](double t) {
      const double a = 2 * M_PI * t / T;
      return Pose::FromTranslation(Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0));
    });
  }
  if (kind == "replay") {
    if (rest.empty()) Fail(where, "expected replay:FILE.csv");
    return std::make_unique<ReplayDevice>(ReadTrajectoryCsv(rest), SimDeviceParams::DefaultCapabilities());
  }
  if (kind == "udp") {
    std::vector<std::string> f = Split(rest, ':');
    UdpDeviceParams p;
    // udp:ADDRESS:... when the first field is an address (it has dots).
    if (!f.empty() && f[0].find('.') != std::string::npos) {
      if (!ParseIpv4(f[0], &p.bind_address)) Fail(where, "'" + f[0] + "' is not an IPv4 address (a.b.c.d)");
      f.erase(f.begin());
    }
    if (f.empty() || f[0].empty() || f.size() > 2) Fail(where, "expected udp:[ADDRESS:]LISTEN_PORT[:PEER_PORT]");
    p.listen_port = ParsePort(f[0], spec);
    if (f.size() > 1) p.peer_port = ParsePort(f[1], spec);
    for (const std::string& peer : options.peers) {
      std::uint32_t a = 0;
      if (!ParseIpv4(peer, &a)) Fail("--device-peer", "'" + QuoteToken(peer) + "' is not an IPv4 address (a.b.c.d)");
      if (const char* kind = NotAHostAddress(a))
        Fail("--device-peer", peer + " is " + kind + ": no datagram comes from it (give the device computer's address)");
      p.allowed_peers.push_back(a);
    }
    p.capabilities = SimDeviceParams::DefaultCapabilities();
    return std::make_unique<UdpDevice>(p);
  }
  if (kind == "spacenav") {
#ifdef CONTACTLAB_HAVE_SPNAV
    return std::make_unique<SpacenavDevice>(SpacenavParams{});
#else
    Fail(where, "this build has no spacenav support (libspnav was not found at configure time)");
#endif
  }
  if (kind == "plugin") {
    if (rest.empty()) Fail(where, "expected plugin:LIBRARY.so[?CONFIG]");
    const std::size_t q = rest.find('?');
    return std::make_unique<PluginDevice>(rest.substr(0, q), q == std::string::npos ? "" : rest.substr(q + 1));
  }
  Fail(where, "unknown device kind '" + kind + "' (expected sim, replay, udp, spacenav or plugin)");
}

}  // namespace contactlab
