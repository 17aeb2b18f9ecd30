// libFuzzer target: the UDP packet decoders (haptics/udp_protocol.cc) on arbitrary datagrams,
// and on the same bytes made 88 long with a correct checksum so mutations reach the fields.
// Beyond not crashing, an accepted packet must hold what the receiver relies on: finite
// numbers, and a quaternion that normalises to a unit rotation (udp_device.cc normalises it).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "haptics/udp_protocol.h"

namespace {

using namespace contactlab::udp;

void CheckPose(const std::uint8_t* data, std::size_t size) {
  PosePacket p;
  if (DecodePose(data, size, &p) != DecodeStatus::kOk) return;
  for (double v : p.position) {
    if (!std::isfinite(v)) __builtin_trap();
  }
  const Eigen::Quaterniond q(p.quaternion[0], p.quaternion[1], p.quaternion[2], p.quaternion[3]);
  if (!(std::abs(q.normalized().norm() - 1.0) < 1e-9)) __builtin_trap();
  // What was accepted encodes back to the same bytes.
  PoseBytes again;
  EncodePose(p, &again);
  if (std::memcmp(again.data(), data, kPosePacketSize) != 0) __builtin_trap();
}

void CheckWrench(const std::uint8_t* data, std::size_t size) {
  WrenchPacket w;
  if (DecodeWrench(data, size, &w) != DecodeStatus::kOk) return;
  for (double v : w.force) {
    if (!std::isfinite(v)) __builtin_trap();
  }
  for (double v : w.torque) {
    if (!std::isfinite(v)) __builtin_trap();
  }
  WrenchBytes again;
  EncodeWrench(w, &again);
  if (std::memcmp(again.data(), data, kWrenchPacketSize) != 0) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // As received.
  CheckPose(data, size);
  CheckWrench(data, size);
  // As a well-formed datagram: 88 bytes, header forced to the type the first byte picks,
  // checksum recomputed.
  static_assert(kPosePacketSize == kWrenchPacketSize);
  std::uint8_t packet[kPosePacketSize] = {};
  std::memcpy(packet, data, std::min(size, kPosePacketSize));
  const bool pose = size == 0 || (data[0] & 1) == 0;
  const std::uint32_t magic = pose ? kPoseMagic : kWrenchMagic;
  const std::uint16_t type = pose ? kTypePose : kTypeWrench;
  std::memcpy(packet, &magic, 4);
  std::memcpy(packet + 4, &kVersion, 2);
  std::memcpy(packet + 6, &type, 2);
  const std::uint32_t crc = Crc32(packet, kPosePacketSize - 4);
  std::memcpy(packet + kPosePacketSize - 4, &crc, 4);
  if (pose) {
    CheckPose(packet, kPosePacketSize);
  } else {
    CheckWrench(packet, kWrenchPacketSize);
  }
  return 0;
}
