// A haptic device reached over UDP on loopback (see UDP_PROTOCOL.md).
#include "haptics/udp_device.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <string>

#include "util/error.h"

namespace contactlab {
namespace {

// A - B, saturated to the int64 range (timestamps come from the network: any value).
std::int64_t SatSub(std::int64_t a, std::int64_t b) {
  std::int64_t d;
  if (!__builtin_sub_overflow(a, b, &d)) return d;
  return b < 0 ? std::numeric_limits<std::int64_t>::max() : std::numeric_limits<std::int64_t>::min();
}

}  // namespace

std::string Ipv4Text(std::uint32_t address) {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 255) + "." +
         std::to_string((address >> 8) & 255) + "." + std::to_string(address & 255);
}

bool ParseIpv4(const std::string& text, std::uint32_t* address) {
  in_addr a{};
  if (::inet_pton(AF_INET, text.c_str(), &a) != 1) return false;
  *address = ntohl(a.s_addr);
  return true;
}

const char* NotAHostAddress(std::uint32_t address) {
  if ((address >> 24) == 0) return "the unspecified address";
  if (address == 0xffffffffu) return "the broadcast address";
  if ((address >> 28) == 0xe) return "a multicast address";
  if ((address >> 28) == 0xf) return "a reserved address";
  return nullptr;
}

namespace {
bool IsLoopback(std::uint32_t address) { return (address >> 24) == 127; }
}  // namespace

UdpDevice::UdpDevice(const UdpDeviceParams& params) : params_(params) {
  const std::string where = "udp device " + Ipv4Text(params.bind_address) + ":" + std::to_string(params.listen_port);
  if (!IsLoopback(params.bind_address) && params.allowed_peers.empty()) {
    Fail(where, "binding " + Ipv4Text(params.bind_address) +
                    " (off the loopback) needs the senders to accept: --device-peer ADDRESS, once per device computer");
  }
  for (const std::uint32_t peer : params.allowed_peers) {
    if (const char* kind = NotAHostAddress(peer))
      Fail(where, "allowed peer " + Ipv4Text(peer) + " is " + kind + ", never the sender of a datagram");
  }
  if (params.allowed_peers.size() == 1) peer_address_.store(params.allowed_peers.front());
  if (!(params.stale_seconds > 0 && params.stale_seconds < 1e6)) Fail(where, "stale_seconds must lie in (0, 1e6)");
  if (!(params.resync_seconds > 0 && params.resync_seconds < 1e6)) Fail(where, "resync_seconds must lie in (0, 1e6)");
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) Fail(where, std::string("cannot open a UDP socket: ") + std::strerror(errno));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(params.listen_port);
  addr.sin_addr.s_addr = htonl(params.bind_address);
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    const int e = errno;
    ::close(fd_);
    Fail(where, std::string("cannot bind: ") + std::strerror(e));
  }
  socklen_t len = sizeof(addr);
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  bound_port_ = ntohs(addr.sin_port);
  peer_port_.store(params.peer_port);
}

UdpDevice::~UdpDevice() {
  if (fd_ >= 0) ::close(fd_);
}

bool UdpDevice::Read(std::int64_t now_ns, DeviceState* out) {
  bool fresh = false;
  std::uint8_t buf[512];  // larger than a packet, so over-long datagrams are seen as such
  for (;;) {
    sockaddr_in from{};
    socklen_t from_len = sizeof(from);
    const ssize_t n = ::recvfrom(fd_, buf, sizeof(buf), MSG_TRUNC, reinterpret_cast<sockaddr*>(&from), &from_len);
    if (n < 0) break;  // EAGAIN: drained (other errors: nothing to act on this cycle)
    ++stats_.datagrams;
    // Only the senders allowed: loopback ones, or the listed peers.
    const std::uint32_t sender = ntohl(from.sin_addr.s_addr);
    bool allowed = params_.allowed_peers.empty() && IsLoopback(sender);
    for (const std::uint32_t a : params_.allowed_peers) allowed = allowed || a == sender;
    if (!allowed) {
      ++stats_.foreign;
      stats_.last_foreign_address = sender;
      continue;
    }
    // Decode and classify; a rejected packet changes nothing but its counter.
    udp::PosePacket p;
    const udp::DecodeStatus s = udp::DecodePose(buf, std::size_t(n) > sizeof(buf) ? sizeof(buf) + 1 : std::size_t(n), &p);
    switch (s) {
      case udp::DecodeStatus::kOk: break;
      case udp::DecodeStatus::kBadLength: ++stats_.bad_length; continue;
      case udp::DecodeStatus::kBadMagic:
      case udp::DecodeStatus::kBadVersion:
      case udp::DecodeStatus::kBadType: ++stats_.bad_header; continue;
      case udp::DecodeStatus::kBadChecksum: ++stats_.bad_checksum; continue;
      case udp::DecodeStatus::kNonFinite: ++stats_.non_finite; continue;
    }
    // A new stream: nothing accepted for resync_seconds (the sender fell silent, or every
    // packet since was rejected), or a sequence far behind the last accepted (the sender
    // restarted its count). The packet then sets the sequence and the delay reference.
    if (have_pose_) {
      const bool silence = SatSub(now_ns, last_accept_ns_) > std::int64_t(params_.resync_seconds * 1e9);
      const bool restart = p.sequence < last_sequence_ && last_sequence_ - p.sequence > params_.reorder_window;
      if (silence || restart) {
        have_pose_ = false;
        ++stats_.resyncs;
      }
    }
    if (have_pose_ && p.sequence == last_sequence_) {
      ++stats_.duplicate;
      continue;
    }
    if (have_pose_ && p.sequence < last_sequence_) {
      ++stats_.out_of_order;
      continue;
    }
    const std::int64_t delay = SatSub(now_ns, p.timestamp_ns);
    const std::int64_t tolerance = std::int64_t(params_.stale_seconds * 1e9);
    if (have_pose_ && SatSub(delay, min_delay_ns_) > tolerance) {
      ++stats_.stale;
      continue;
    }
    if (have_pose_ && SatSub(min_delay_ns_, delay) > tolerance) {
      ++stats_.future;
      continue;
    }
    // Accept.
    if (!have_pose_ || delay < min_delay_ns_) min_delay_ns_ = delay;
    have_pose_ = true;
    last_sequence_ = p.sequence;
    last_accept_ns_ = now_ns;
    Eigen::Quaterniond q(p.quaternion[0], p.quaternion[1], p.quaternion[2], p.quaternion[3]);
    last_.X_WD = Pose{q.normalized(), Eigen::Vector3d(p.position[0], p.position[1], p.position[2])};
    last_.timestamp_ns = p.timestamp_ns;
    last_.buttons = p.buttons;
    last_.sequence = p.sequence;
    if (params_.peer_port == 0) peer_port_.store(ntohs(from.sin_port), std::memory_order_relaxed);
    peer_address_.store(sender, std::memory_order_relaxed);
    ++stats_.accepted;
    fresh = true;
  }
  *out = last_;
  return fresh;
}

bool UdpDevice::WaitForInput(double timeout_seconds) const {
  pollfd p{};
  p.fd = fd_;
  p.events = POLLIN;
  const int timeout_ms = timeout_seconds <= 0 ? 0 : timeout_seconds >= 1e6 ? 1000000000 : int(timeout_seconds * 1e3);
  for (;;) {
    const int n = ::poll(&p, 1, timeout_ms);
    if (n < 0 && errno == EINTR) continue;  // a signal: wait again (the full timeout, an upper bound)
    return n > 0 && (p.revents & POLLIN);
  }
}

bool UdpDevice::Send(const Wrench& w, std::int64_t now_ns, std::uint32_t flags, std::uint64_t pose_sequence) noexcept {
  const std::uint32_t port = peer_port_.load(std::memory_order_relaxed);
  if (port == 0) return false;  // nobody to talk to yet
  udp::WrenchPacket pkt;
  pkt.sequence = wrench_sequence_.fetch_add(1, std::memory_order_relaxed) + 1;
  pkt.timestamp_ns = now_ns;
  for (int i = 0; i < 3; ++i) {
    pkt.force[i] = w.force[i];
    pkt.torque[i] = w.torque[i];
  }
  pkt.pose_sequence = pose_sequence;
  pkt.flags = flags;
  udp::WrenchBytes bytes;
  udp::EncodeWrench(pkt, &bytes);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(std::uint16_t(port));
  to.sin_addr.s_addr = htonl(peer_address_.load(std::memory_order_relaxed));
  return ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof(to)) ==
         ssize_t(bytes.size());
}

void UdpDevice::Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) {
  if (peer_port_.load(std::memory_order_relaxed) == 0) return;
  // Bit 31 is reserved for the watchdog's emergency zero.
  if (Send(wrench, now_ns, safety_flags & ~kEmergencyZeroFlag, last_sequence_)) {
    ++stats_.wrenches_sent;
  } else {
    ++stats_.send_errors;
  }
}

DeviceInputStats UdpDevice::input_stats() const {
  DeviceInputStats d;
  d.received = stats_.datagrams;
  d.accepted = stats_.accepted;
  d.malformed = stats_.bad_length + stats_.bad_header + stats_.bad_checksum + stats_.non_finite;
  d.duplicate = stats_.duplicate;
  d.out_of_order = stats_.out_of_order;
  d.stale = stats_.stale;
  d.future = stats_.future;
  d.resyncs = stats_.resyncs;
  d.foreign = stats_.foreign;
  d.last_foreign_address = stats_.last_foreign_address;
  return d;
}

std::string UdpDevice::description() const {
  std::string s = "udp on " + Ipv4Text(params_.bind_address) + ":" + std::to_string(bound_port_) + ", wrenches to ";
  const std::string to = params_.allowed_peers.size() == 1 ? Ipv4Text(params_.allowed_peers.front()) : "the sender";
  s += params_.peer_port != 0 ? to + ":" + std::to_string(params_.peer_port) : "the sender of the poses";
  if (params_.allowed_peers.empty()) {
    s += ", accepting loopback senders only";
  } else {
    s += ", accepting only";
    for (const std::uint32_t a : params_.allowed_peers) s += " " + Ipv4Text(a);
  }
  return s;
}

void UdpDevice::EmergencyZero() noexcept {
  // From any thread: a zero wrench flagged kEmergencyZeroFlag; touches only atomics, and the
  // kernel sends each datagram whole.
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  if (Send(Wrench{}, std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec, kEmergencyZeroFlag, 0))
    emergency_zeroes_.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace contactlab
