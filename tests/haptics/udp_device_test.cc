// Tests of the UDP device protocol on loopback sockets (UDP_PROTOCOL.md): round trips, and
// short, malformed, duplicated, out-of-order and stale packets rejected, counted, never acted on.
#include "haptics/udp_device.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <limits>

#include "haptics/device_factory.h"
#include "haptics/haptic_cycle.h"
#include "haptics/haptic_loop.h"
#include "haptics/safety_filter.h"
#include "haptics/sim_device.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr std::int64_t kMs = 1000000;

// The device side of the protocol: a loopback socket talking to the UdpDevice's port.
class Peer {
 public:
  // A sender from SOURCE (host order; every address of 127.0.0.0/8 is this machine on Linux, so
  // 127.0.0.2 and 127.0.0.3 stand for two other computers).
  explicit Peer(std::uint16_t device_port, std::uint32_t source = INADDR_LOOPBACK) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in self{};
    self.sin_family = AF_INET;
    self.sin_addr.s_addr = htonl(source);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&self), sizeof(self));
    timeval tv{30, 0};  // a hang guard for Receive, far above any loopback delay
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    to_.sin_family = AF_INET;
    to_.sin_port = htons(device_port);
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  }
  ~Peer() { ::close(fd_); }
  void SendRaw(const std::uint8_t* d, std::size_t n) {
    ASSERT_EQ(::sendto(fd_, d, n, 0, reinterpret_cast<sockaddr*>(&to_), sizeof(to_)), ssize_t(n));
    ++sent_;
  }
  // Datagrams sent to the device so far.
  std::int64_t sent() const { return sent_; }
  void SendPose(std::uint64_t seq, std::int64_t ts, double x) {
    udp::PosePacket p;
    p.sequence = seq;
    p.timestamp_ns = ts;
    p.position[0] = x;
    p.buttons = 5;
    udp::PoseBytes b;
    udp::EncodePose(p, &b);
    SendRaw(b.data(), b.size());
  }
  // Receives one datagram (blocking, 30 s hang guard); returns its size or -1.
  ssize_t Receive(std::uint8_t* buf, std::size_t cap) { return ::recv(fd_, buf, cap, 0); }

 private:
  int fd_;
  sockaddr_in to_{};
  std::int64_t sent_ = 0;
};

// Parameters of a device with force output, for a HapticCycle.
UdpDeviceParams WithForceOutput() {
  UdpDeviceParams p;
  p.capabilities = SimDeviceParams::DefaultCapabilities();
  return p;
}

// Real time a test waits for a datagram before it gives up: a hang guard, far above any
// loopback delay (which is usually none: the kernel delivers within sendto).
constexpr double kArrivalGuardSeconds = 30;

// Reads DEV at NOW_NS until every datagram PEER has sent so far has arrived (the device's
// datagram counter), waiting on the socket between reads: loopback delivery is usually
// complete when sendto returns, but not promised, so datagrams sent together may take more
// than one read. Returns whether any of the reads gave a fresh pose; *S holds the last
// read's state.
bool ReadWhenArrived(UdpDevice& dev, const Peer& peer, std::int64_t now_ns, DeviceState* s) {
  bool fresh = false;
  while (dev.stats().datagrams < peer.sent()) {
    if (!dev.WaitForInput(kArrivalGuardSeconds)) {
      ADD_FAILURE() << "received " << dev.stats().datagrams << " of " << peer.sent() << " datagrams";
      break;
    }
    fresh = dev.Read(now_ns, s) || fresh;
  }
  return fresh;
}

TEST(UdpProtocol, PoseAndWrenchRoundTripBitExactly) {
  udp::PosePacket p;
  p.sequence = 0x0123456789abcdefULL;
  p.timestamp_ns = -42;
  p.position[0] = 1.0 / 3.0, p.position[1] = -2e-300, p.position[2] = 7;
  p.quaternion[0] = 0.5, p.quaternion[1] = 0.5, p.quaternion[2] = -0.5, p.quaternion[3] = 0.5;
  p.buttons = 0x80000001u;
  udp::PoseBytes pb;
  udp::EncodePose(p, &pb);
  EXPECT_EQ(pb[0], 'C');
  EXPECT_EQ(pb[1], 'L');
  EXPECT_EQ(pb[2], 'P');
  EXPECT_EQ(pb[3], '1');
  EXPECT_EQ(pb[8], 0xef);  // little-endian sequence
  udp::PosePacket q;
  ASSERT_EQ(udp::DecodePose(pb.data(), pb.size(), &q), udp::DecodeStatus::kOk);
  EXPECT_EQ(q.sequence, p.sequence);
  EXPECT_EQ(q.timestamp_ns, p.timestamp_ns);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(q.position[i], p.position[i]);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(q.quaternion[i], p.quaternion[i]);
  EXPECT_EQ(q.buttons, p.buttons);

  udp::WrenchPacket w;
  w.sequence = 9;
  w.timestamp_ns = 123456789;
  w.force[2] = -1.5;
  w.torque[0] = 0.25;
  w.pose_sequence = 8;
  w.flags = 3;
  udp::WrenchBytes wb;
  udp::EncodeWrench(w, &wb);
  udp::WrenchPacket v;
  ASSERT_EQ(udp::DecodeWrench(wb.data(), wb.size(), &v), udp::DecodeStatus::kOk);
  EXPECT_EQ(v.force[2], -1.5);
  EXPECT_EQ(v.torque[0], 0.25);
  EXPECT_EQ(v.pose_sequence, 8u);
  EXPECT_EQ(v.flags, 3u);
  // A wrench packet is not a pose packet.
  EXPECT_EQ(udp::DecodePose(wb.data(), wb.size(), &q), udp::DecodeStatus::kBadMagic);
}

TEST(UdpProtocol, ChecksumIsStandardCrc32) {
  const char* check = "123456789";
  EXPECT_EQ(udp::Crc32(reinterpret_cast<const std::uint8_t*>(check), 9), 0xCBF43926u);
}

TEST(UdpProtocol, EverySingleBitFlipIsDetected) {
  udp::PosePacket p;
  p.sequence = 77;
  p.position[1] = 0.01;
  udp::PoseBytes pb;
  udp::EncodePose(p, &pb);
  udp::PosePacket q;
  for (std::size_t byte = 0; byte < pb.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      udp::PoseBytes c = pb;
      c[byte] ^= std::uint8_t(1u << bit);
      ASSERT_NE(udp::DecodePose(c.data(), c.size(), &q), udp::DecodeStatus::kOk) << "byte " << byte << " bit " << bit;
    }
  }
}

// A quaternion whose squared norm overflows (components near 1e200) is finite component by
// component but normalises to zero: accepted, it would hand the cycle a pose with no rotation.
// Found by tests/fuzz/fuzz_udp_packet.
TEST(UdpProtocol, NonFiniteOrOverflowingQuaternionIsRejected) {
  udp::PosePacket p;
  udp::PoseBytes pb;
  udp::PosePacket q;
  for (const double big : {1e200, -1e160, 1.3e154}) {
    SCOPED_TRACE(big);
    p.quaternion[0] = big;
    p.quaternion[1] = big;
    udp::EncodePose(p, &pb);
    EXPECT_EQ(udp::DecodePose(pb.data(), pb.size(), &q), udp::DecodeStatus::kNonFinite);
  }
  // Large but representable quaternions still decode, and normalise to a unit rotation.
  p.quaternion[0] = 1e150;
  p.quaternion[1] = 0;
  udp::EncodePose(p, &pb);
  ASSERT_EQ(udp::DecodePose(pb.data(), pb.size(), &q), udp::DecodeStatus::kOk);
  const Eigen::Quaterniond unit =
      Eigen::Quaterniond(q.quaternion[0], q.quaternion[1], q.quaternion[2], q.quaternion[3]).normalized();
  EXPECT_NEAR(unit.norm(), 1.0, 1e-12);
  p.quaternion[0] = std::numeric_limits<double>::infinity();
  udp::EncodePose(p, &pb);
  EXPECT_EQ(udp::DecodePose(pb.data(), pb.size(), &q), udp::DecodeStatus::kNonFinite);
}

TEST(UdpDevice, BadPacketsAreRejectedCountedAndNeverActedOn) {
  UdpDevice dev(UdpDeviceParams{});
  ASSERT_GT(dev.bound_port(), 0);
  Peer peer(dev.bound_port());
  DeviceState s;
  const std::int64_t t0 = 1000 * kMs;

  // A good packet is accepted.
  peer.SendPose(10, t0, 0.01);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.01);
  EXPECT_EQ(s.sequence, 10u);
  EXPECT_EQ(s.buttons, 5u);

  // Short, long, corrupted, bad magic, non-finite, duplicate, out of order, stale.
  udp::PosePacket p;
  p.sequence = 11;
  p.timestamp_ns = t0 + kMs;
  p.position[0] = 9.0;
  udp::PoseBytes b;
  udp::EncodePose(p, &b);
  peer.SendRaw(b.data(), 10);                               // short
  std::uint8_t longer[100] = {0};
  std::memcpy(longer, b.data(), b.size());
  peer.SendRaw(longer, sizeof(longer));                     // long
  udp::PoseBytes c = b;
  c[40] ^= 0x01;
  peer.SendRaw(c.data(), c.size());                         // checksum
  c = b;
  c[0] = 'X';
  peer.SendRaw(c.data(), c.size());                         // magic (checksum not reached)
  udp::PosePacket nf = p;
  nf.position[1] = std::numeric_limits<double>::infinity();
  udp::EncodePose(nf, &c);
  peer.SendRaw(c.data(), c.size());                         // non-finite
  peer.SendPose(10, t0 + kMs, 9.0);                         // duplicate of the accepted 10
  peer.SendPose(7, t0 + kMs, 9.0);                          // out of order
  peer.SendPose(12, t0 - 200 * kMs, 9.0);                   // stale: 200 ms older than expected
  EXPECT_FALSE(ReadWhenArrived(dev, peer, t0 + 2 * kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.01) << "a rejected packet was acted on";
  EXPECT_EQ(s.sequence, 10u);
  const UdpStats& st = dev.stats();
  EXPECT_EQ(st.bad_length, 2);
  EXPECT_EQ(st.bad_checksum, 1);
  EXPECT_EQ(st.bad_header, 1);
  EXPECT_EQ(st.non_finite, 1);
  EXPECT_EQ(st.duplicate, 1);
  EXPECT_EQ(st.out_of_order, 1);
  EXPECT_EQ(st.stale, 1);
  EXPECT_EQ(st.accepted, 1);
  EXPECT_EQ(st.rejected(), 8);

  // The stream resumes with newer packets; a read keeps the newest of those queued (and
  // should they arrive in two reads, the second keeps the newer one).
  peer.SendPose(13, t0 + 3 * kMs, 0.02);
  peer.SendPose(14, t0 + 3 * kMs, 0.03);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + 4 * kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.03);
  EXPECT_EQ(dev.stats().accepted, 3);
}

TEST(UdpDevice, WrenchPacketsGoBackToTheSenderAndEmergencyZeroIsFlagged) {
  UdpDevice dev(UdpDeviceParams{});
  Peer peer(dev.bound_port());
  DeviceState s;
  peer.SendPose(1, 0, 0.0);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, kMs, &s));
  Wrench w;
  w.force = Eigen::Vector3d(1, 2, 3);
  w.torque = Eigen::Vector3d(-0.1, 0, 0.1);
  dev.Write(w, 2 * kMs, 0);
  std::uint8_t buf[256];
  ssize_t n = peer.Receive(buf, sizeof(buf));
  ASSERT_EQ(n, ssize_t(udp::kWrenchPacketSize));
  udp::WrenchPacket got;
  ASSERT_EQ(udp::DecodeWrench(buf, std::size_t(n), &got), udp::DecodeStatus::kOk);
  EXPECT_EQ(got.force[1], 2.0);
  EXPECT_EQ(got.torque[2], 0.1);
  EXPECT_EQ(got.pose_sequence, 1u);
  EXPECT_EQ(got.timestamp_ns, 2 * kMs);

  dev.EmergencyZero();
  n = peer.Receive(buf, sizeof(buf));
  ASSERT_EQ(udp::DecodeWrench(buf, std::size_t(n), &got), udp::DecodeStatus::kOk);
  EXPECT_EQ(got.force[0], 0.0);
  EXPECT_EQ(got.force[1], 0.0);
  EXPECT_TRUE(got.flags & UdpDevice::kEmergencyZeroFlag);
  EXPECT_EQ(dev.emergency_zeroes(), 1);
}

TEST(UdpDevice, OffTheLoopbackOnlyTheListedPeersAreAcceptedAndOthersAreNamed) {
  UdpDeviceParams p = WithForceOutput();
  p.bind_address = 0;                // 0.0.0.0: every interface
  p.allowed_peers = {0x7f000002};    // 127.0.0.2
  UdpDevice dev(p);
  EXPECT_NE(dev.description().find("udp on 0.0.0.0:"), std::string::npos) << dev.description();
  EXPECT_NE(dev.description().find("accepting only 127.0.0.2"), std::string::npos) << dev.description();
  Peer allowed(dev.bound_port(), 0x7f000002), other(dev.bound_port(), 0x7f000003);
  DeviceState s;
  other.SendPose(1, 0, 0.5);
  EXPECT_FALSE(ReadWhenArrived(dev, other, kMs, &s));
  EXPECT_EQ(dev.stats().foreign, 1);
  EXPECT_EQ(dev.stats().last_foreign_address, 0x7f000003u);
  EXPECT_EQ(dev.stats().accepted, 0);
  allowed.SendPose(1, 0, 0.25);
  while (dev.stats().datagrams < other.sent() + allowed.sent()) {
    ASSERT_TRUE(dev.WaitForInput(kArrivalGuardSeconds)) << "the allowed peer's pose did not arrive";
    dev.Read(kMs, &s);
  }
  EXPECT_EQ(dev.stats().accepted, 1);
  EXPECT_EQ(s.X_WD.translation.x(), 0.25);
  // The wrench goes back to the accepted sender.
  Wrench w;
  w.force = Eigen::Vector3d(0, 0, 1.5);
  dev.Write(w, 2 * kMs, 0);
  std::uint8_t buf[256];
  const ssize_t n = allowed.Receive(buf, sizeof(buf));
  udp::WrenchPacket got;
  ASSERT_EQ(udp::DecodeWrench(buf, std::size_t(n), &got), udp::DecodeStatus::kOk);
  EXPECT_EQ(got.force[2], 1.5);
  // The refusals reach the report, with the sender's address.
  EXPECT_EQ(dev.input_stats().foreign, 1);
  const std::string report = FormatDeviceInputStats(dev.input_stats());
  EXPECT_NE(report.find("refused 1 from senders not allowed (latest 127.0.0.3)"), std::string::npos) << report;
}

TEST(UdpDevice, AnAddressOffTheLoopbackNeedsItsPeersAndTheSpecSaysSo) {
  UdpDeviceParams p;
  p.bind_address = 0;
  try {
    UdpDevice dev(p);
    ADD_FAILURE() << "bound 0.0.0.0 with no peers";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--device-peer"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("0.0.0.0"), std::string::npos) << e.what();
  }
  EXPECT_EQ(MakeDevice("udp:0.0.0.0:0", DeviceOptions{{"127.0.0.2"}})->name(), "udp");
  auto error_of = [](const std::string& spec, const std::vector<std::string>& peers) {
    try {
      MakeDevice(spec, DeviceOptions{peers});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("udp:0.0.0.0:0", {}).find("--device-peer"), std::string::npos);
  EXPECT_NE(error_of("udp:1.2.3:0", {}).find("'1.2.3' is not an IPv4 address"), std::string::npos);
  EXPECT_NE(error_of("udp:0.0.0.0:0", {"nope"}).find("--device-peer: 'nope' is not an IPv4 address"), std::string::npos)
      << error_of("udp:0.0.0.0:0", {"nope"});
  EXPECT_NE(error_of("sim", {"127.0.0.2"}).find("--device-peer: applies to udp devices only"), std::string::npos);
  EXPECT_NE(error_of("udp:127.0.0.1:", {}).find("expected udp:[ADDRESS:]LISTEN_PORT[:PEER_PORT]"), std::string::npos);
}

TEST(UdpDevice, PortInUseIsReportedWithThePort) {
  UdpDevice a(UdpDeviceParams{});
  UdpDeviceParams p;
  p.listen_port = a.bound_port();
  try {
    UdpDevice b(p);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(a.bound_port())), std::string::npos) << e.what();
  }
}

// One packet stamped 10 s ahead must not become the clock reference that makes every later
// packet stale: it is rejected as "future", and the stream goes on.
TEST(UdpDevice, StaleFutureTimestampDoesNotLockTheDeviceOut) {
  UdpDevice dev(UdpDeviceParams{});
  Peer peer(dev.bound_port());
  DeviceState s;
  const std::int64_t t0 = 1000 * kMs;
  peer.SendPose(1, t0, 0.01);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + kMs, &s));
  peer.SendPose(2, t0 + 10000 * kMs, 0.5);  // 10 s in the future
  EXPECT_FALSE(ReadWhenArrived(dev, peer, t0 + 2 * kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.01);
  EXPECT_EQ(dev.stats().future, 1);
  for (int i = 3; i < 10; ++i) {
    peer.SendPose(std::uint64_t(i), t0 + i * kMs, 0.001 * i);
    ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + (i + 1) * kMs, &s)) << "packet " << i << " refused";
    EXPECT_EQ(s.X_WD.translation.x(), 0.001 * i);
  }
  EXPECT_EQ(dev.stats().stale, 0);
  EXPECT_EQ(dev.stats().accepted, 8);
  EXPECT_EQ(dev.input_stats().future, 1);
}

// The same packet as the very first one: it sets the reference, the real stream is stale
// until resync_seconds pass without an accepted packet; then the device resynchronises.
TEST(UdpDevice, FutureFirstPacketIsForgottenAfterResyncSeconds) {
  UdpDeviceParams params;
  params.resync_seconds = 0.1;
  UdpDevice dev(params);
  Peer peer(dev.bound_port());
  DeviceState s;
  const std::int64_t t0 = 1000 * kMs;
  peer.SendPose(1, t0 + 10000 * kMs, 0.5);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0, &s));
  bool recovered = false;
  std::int64_t recovered_at = 0;
  for (int i = 2; i < 300 && !recovered; ++i) {
    peer.SendPose(std::uint64_t(i), t0 + i * kMs, 0.001);
    recovered = ReadWhenArrived(dev, peer, t0 + i * kMs, &s);
    recovered_at = i;
  }
  ASSERT_TRUE(recovered) << "the device stayed locked out";
  EXPECT_LE(recovered_at, 102);  // within resync_seconds (100 ms of cycles)
  EXPECT_EQ(s.X_WD.translation.x(), 0.001);
  EXPECT_EQ(dev.stats().resyncs, 1);
  // And it stays in sync.
  peer.SendPose(1000, t0 + (recovered_at + 1) * kMs, 0.002);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + (recovered_at + 1) * kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.002);
  EXPECT_EQ(dev.stats().resyncs, 1);
}

// One packet with sequence 2^63 must not make every later packet "out of order": the real
// sender's next packet lies far behind it, which reads as a sender restart.
TEST(UdpDevice, HugeSequenceNumberDoesNotLockTheDeviceOut) {
  UdpDevice dev(UdpDeviceParams{});
  Peer peer(dev.bound_port());
  DeviceState s;
  const std::int64_t t0 = 1000 * kMs;
  peer.SendPose(1, t0, 0.01);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + kMs, &s));
  peer.SendPose(std::uint64_t(1) << 63, t0 + kMs, 0.5);
  ReadWhenArrived(dev, peer, t0 + 2 * kMs, &s);
  for (int i = 2; i < 10; ++i) {
    peer.SendPose(std::uint64_t(i), t0 + i * kMs, 0.001 * i);
    ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + (i + 1) * kMs, &s)) << "packet " << i << " refused";
    EXPECT_EQ(s.X_WD.translation.x(), 0.001 * i);
  }
  EXPECT_EQ(dev.stats().out_of_order, 0);
  EXPECT_EQ(dev.stats().resyncs, 1);
}

// A sender that restarts from sequence 0 (and a new clock origin) after a pause is accepted.
TEST(UdpDevice, SenderRestartAfterASilenceIsAccepted) {
  UdpDevice dev(UdpDeviceParams{});
  Peer peer(dev.bound_port());
  DeviceState s;
  const std::int64_t t0 = 1000 * kMs;
  for (int i = 1; i <= 5; ++i) peer.SendPose(std::uint64_t(100 + i), t0 + i * kMs, 0.01);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + 6 * kMs, &s));
  // Restarted: sequence from 0, its clock 50 s behind; first within the silence (refused),
  // then after it (accepted).
  peer.SendPose(0, 7 * kMs, 0.02);
  EXPECT_FALSE(ReadWhenArrived(dev, peer, t0 + 7 * kMs, &s));
  peer.SendPose(1, 400 * kMs, 0.03);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + 400 * kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.03);
  peer.SendPose(2, 401 * kMs, 0.04);
  ASSERT_TRUE(ReadWhenArrived(dev, peer, t0 + 401 * kMs, &s));
  EXPECT_EQ(s.X_WD.translation.x(), 0.04);
  EXPECT_EQ(dev.stats().resyncs, 1);
}

// The wrench packet's flags field carries the cycle's SafetyFlag bits (UDP_PROTOCOL.md).
TEST(UdpDevice, WrenchPacketCarriesTheCycleSafetyFlags) {
  UdpDevice dev(WithForceOutput());
  Peer peer(dev.bound_port());
  peer.SendPose(1, 0, 0.0);
  ASSERT_TRUE(dev.WaitForInput(kArrivalGuardSeconds));  // the cycle's first read gets the pose
  HapticCycle cycle(dev, nullptr, HapticCycleConfig{});
  cycle.Start(0);
  const CycleRecord rec = cycle.Step(kMs);  // inside the start ramp
  ASSERT_TRUE(rec.safety_flags & kSafetyRamping);
  std::uint8_t buf[256];
  const ssize_t n = peer.Receive(buf, sizeof(buf));
  ASSERT_EQ(n, ssize_t(udp::kWrenchPacketSize));
  udp::WrenchPacket got;
  ASSERT_EQ(udp::DecodeWrench(buf, std::size_t(n), &got), udp::DecodeStatus::kOk);
  EXPECT_EQ(got.flags, rec.safety_flags);
  EXPECT_FALSE(got.flags & UdpDevice::kEmergencyZeroFlag);

  // A silent device: the watchdog flag travels too.
  const CycleRecord silent = cycle.Step(200 * kMs);
  ASSERT_TRUE(silent.safety_flags & kSafetyDeviceSilent);
  ASSERT_EQ(peer.Receive(buf, sizeof(buf)), ssize_t(udp::kWrenchPacketSize));
  ASSERT_EQ(udp::DecodeWrench(buf, udp::kWrenchPacketSize, &got), udp::DecodeStatus::kOk);
  EXPECT_EQ(got.flags, silent.safety_flags);
}

// The rejection counters reach each cycle record (the session's status line) and the loop
// report (its summary).
TEST(UdpDevice, RejectionCountersReachTheCycleRecordAndTheSummary) {
  UdpDevice dev(WithForceOutput());
  Peer peer(dev.bound_port());
  const std::int64_t t0 = 1000 * kMs;
  peer.SendPose(10, t0, 0.0);
  peer.SendPose(9, t0, 0.0);                     // out of order
  peer.SendPose(11, t0 - 300 * kMs, 0.0);        // stale
  peer.SendPose(12, t0 + 10000 * kMs, 0.0);      // future
  std::uint8_t junk[20] = {0};
  peer.SendRaw(junk, sizeof(junk));              // malformed
  // Read once all five have arrived, at the cycle's time: the counters are the device's
  // totals, which the cycle's own read then reports.
  DeviceState s;
  ReadWhenArrived(dev, peer, t0 + kMs, &s);
  HapticCycle cycle(dev, nullptr, HapticCycleConfig{});
  cycle.Start(t0);
  const CycleRecord rec = cycle.Step(t0 + kMs);
  EXPECT_EQ(rec.device_input.received, 5);
  EXPECT_EQ(rec.device_input.accepted, 1);
  EXPECT_EQ(rec.device_input.out_of_order, 1);
  EXPECT_EQ(rec.device_input.stale, 1);
  EXPECT_EQ(rec.device_input.future, 1);
  EXPECT_EQ(rec.device_input.malformed, 1);
  EXPECT_EQ(rec.device_input.rejected(), 4);

  HapticLoopReport report;
  report.device_input = dev.input_stats();
  const std::string text = FormatLoopReport(report);
  EXPECT_NE(text.find("rejected 4 (malformed 1, duplicate 0, out of order 1, stale 1, future 1)"), std::string::npos)
      << text;
}

// udp:0 lets the system pick the port; the device says which, for the session to print.
TEST(UdpDevice, RandomPortIsReported) {
  auto dev = MakeDevice("udp:0");
  const auto* udp = dynamic_cast<const UdpDevice*>(dev.get());
  ASSERT_NE(udp, nullptr);
  ASSERT_GT(udp->bound_port(), 0);
  EXPECT_NE(dev->description().find("127.0.0.1:" + std::to_string(udp->bound_port())), std::string::npos)
      << dev->description();
}

}  // namespace
}  // namespace contactlab
