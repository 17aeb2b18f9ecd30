// A haptic device reached over UDP (Barbič & James 2008, sec. 5: pose in, coupling wrench out);
// packets in udp_protocol.h / UDP_PROTOCOL.md. Short, malformed, duplicated, out-of-order and
// stale packets are rejected and counted, never acted on. It binds the loopback interface
// unless told another address, as an explicit opt-in with an allow-list of the senders it
// accepts (a device computer beside the simulation computer); a datagram from any other sender
// is refused and counted with its address.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "haptics/haptic_device.h"
#include "haptics/udp_protocol.h"

namespace contactlab {

struct UdpDeviceParams {
  // The IPv4 address bound (host order): 127.0.0.1, or another address of this machine
  // (0.0.0.0: every interface), which then needs allowed_peers.
  std::uint32_t bind_address = 0x7f000001;
  // Senders accepted (IPv4, host order). Empty: loopback senders (127.0.0.0/8) only.
  std::vector<std::uint32_t> allowed_peers;
  std::uint16_t listen_port = 0;   // port bound; 0 picks a free one (see bound_port())
  std::uint16_t peer_port = 0;     // where wrench packets go (at the sender's address, or the one allowed
                                   // peer before any pose); 0: the port of the last accepted pose's sender
  double stale_seconds = 0.05;     // a packet whose one-way delay exceeds the smallest seen by more is stale,
                                   // one whose delay is below it by more is from the future
  double resync_seconds = 0.25;    // no packet accepted for longer: the next valid one starts a new stream
  std::uint64_t reorder_window = 1000;  // a sequence further behind the last accepted: a sender restart
  DeviceCapabilities capabilities; // what the remote device reports (configuration)
};

struct UdpStats {
  std::int64_t datagrams = 0;          // received
  std::int64_t accepted = 0;
  std::int64_t bad_length = 0;         // short or long
  std::int64_t bad_header = 0;         // magic, version or type
  std::int64_t bad_checksum = 0;
  std::int64_t non_finite = 0;
  std::int64_t duplicate = 0;          // sequence equal to the last accepted
  std::int64_t out_of_order = 0;       // sequence below the last accepted
  std::int64_t stale = 0;              // too old (see UdpDeviceParams::stale_seconds)
  std::int64_t future = 0;             // timestamp ahead of the local clock's elapsed time (same bound)
  std::int64_t resyncs = 0;            // new streams started (after a silence or a sender restart)
  std::int64_t foreign = 0;            // from a sender not allowed (UdpDeviceParams::allowed_peers)
  std::uint32_t last_foreign_address = 0;  // its IPv4 address, host order
  std::int64_t wrenches_sent = 0;
  std::int64_t send_errors = 0;
  std::int64_t rejected() const {
    return bad_length + bad_header + bad_checksum + non_finite + duplicate + out_of_order + stale + future + foreign;
  }
};

// An IPv4 address as text ("a.b.c.d", host order in), and back: false when TEXT is not one.
std::string Ipv4Text(std::uint32_t address);
bool ParseIpv4(const std::string& text, std::uint32_t* address);

// Why ADDRESS (host order) can never be the source of a datagram, so it cannot be an allowed
// peer (nor where wrench packets go): "the unspecified address" (0.0.0.0/8), "a multicast
// address" (224.0.0.0/4), "the broadcast address" (255.255.255.255) or "a reserved address"
// (240.0.0.0/4); nullptr for a host's address.
const char* NotAHostAddress(std::uint32_t address);

class UdpDevice final : public HapticDevice {
 public:
  // Opens a non-blocking UDP socket bound to bind_address:listen_port. Throws Error naming the
  // address and port when the socket cannot be opened or bound, when an address off the
  // loopback comes without allowed peers, or when an allowed peer is no host's address
  // (NotAHostAddress).
  explicit UdpDevice(const UdpDeviceParams& params);
  ~UdpDevice() override;
  UdpDevice(const UdpDevice&) = delete;
  UdpDevice& operator=(const UdpDevice&) = delete;

  std::string_view name() const override { return "udp"; }
  DeviceCapabilities capabilities() const override { return params_.capabilities; }
  // Drains every queued datagram, keeps the newest valid pose. Staleness is judged on the
  // one-way delay NOW_NS - timestamp_ns relative to the smallest delay seen so far, so the
  // two clocks need not share an origin (only a rate); a delay below that reference by more
  // than stale_seconds claims a time the local clock has not reached and is rejected as
  // "future" (it never becomes the reference). A stream resynchronises, taking its sequence
  // and delay reference afresh from the next valid packet, when nothing was accepted for
  // resync_seconds of NOW_NS, or when a sequence lies more than reorder_window behind the
  // last accepted (a sender that restarted): one bad packet cannot lock the device out.
  bool Read(std::int64_t now_ns, DeviceState* out) override;
  // Sends the wrench with SAFETY_FLAGS in the packet's flags field (UDP_PROTOCOL.md).
  void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) override;
  void EmergencyZero() noexcept override;
  DeviceInputStats input_stats() const override;
  // "udp on ADDRESS:PORT, ..." with the bound port (the one picked when listen_port is 0) and
  // the senders it accepts.
  std::string description() const override;

  // Blocks until a datagram is queued on the socket (Read would see it) or TIMEOUT_SECONDS
  // pass; true when one is queued. Not for the haptic loop: for a driver that waits for its
  // device instead of polling it, and for tests that wait for a packet to arrive.
  bool WaitForInput(double timeout_seconds) const;

  std::uint16_t bound_port() const { return bound_port_; }
  const UdpStats& stats() const { return stats_; }
  std::int64_t emergency_zeroes() const { return emergency_zeroes_.load(); }
  // Flag bit set in a wrench packet sent by EmergencyZero.
  static constexpr std::uint32_t kEmergencyZeroFlag = 1u << 31;

 private:
  bool Send(const Wrench& w, std::int64_t now_ns, std::uint32_t flags, std::uint64_t pose_sequence) noexcept;

  UdpDeviceParams params_;
  int fd_ = -1;
  std::uint16_t bound_port_ = 0;
  std::atomic<std::uint32_t> peer_port_{0};
  std::atomic<std::uint32_t> peer_address_{0x7f000001};  // host order: where wrenches go
  std::atomic<std::uint64_t> wrench_sequence_{0};
  std::atomic<std::int64_t> emergency_zeroes_{0};
  bool have_pose_ = false;
  std::uint64_t last_sequence_ = 0;
  std::int64_t min_delay_ns_ = 0;
  std::int64_t last_accept_ns_ = 0;  // NOW_NS of the last accepted packet
  DeviceState last_;
  UdpStats stats_;
};

}  // namespace contactlab
