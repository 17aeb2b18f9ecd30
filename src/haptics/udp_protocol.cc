// Binary UDP packets for networked haptic devices (see UDP_PROTOCOL.md).
#include "haptics/udp_protocol.h"

#include "haptics/haptic_device.h"

#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <utility>

namespace contactlab::udp {
namespace {

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big);

template <typename T>
T ByteSwapIfBig(T v) {
  if constexpr (std::endian::native == std::endian::big) {
    std::uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    std::memcpy(&v, b, sizeof(T));
  }
  return v;
}

template <typename T>
void Put(std::uint8_t* buf, std::size_t* at, T v) {
  v = ByteSwapIfBig(v);
  std::memcpy(buf + *at, &v, sizeof(T));
  *at += sizeof(T);
}

template <typename T>
T Get(const std::uint8_t* buf, std::size_t* at) {
  T v;
  std::memcpy(&v, buf + *at, sizeof(T));
  *at += sizeof(T);
  return ByteSwapIfBig(v);
}

DecodeStatus CheckHeader(const std::uint8_t* d, std::size_t size, std::size_t expected, std::uint32_t magic,
                         std::uint16_t type) {
  if (d == nullptr || size != expected) return DecodeStatus::kBadLength;
  std::size_t at = 0;
  if (Get<std::uint32_t>(d, &at) != magic) return DecodeStatus::kBadMagic;
  if (Get<std::uint16_t>(d, &at) != kVersion) return DecodeStatus::kBadVersion;
  if (Get<std::uint16_t>(d, &at) != type) return DecodeStatus::kBadType;
  at = expected - 4;
  if (Get<std::uint32_t>(d, &at) != Crc32(d, expected - 4)) return DecodeStatus::kBadChecksum;
  return DecodeStatus::kOk;
}

}  // namespace

const char* ToString(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::kOk: return "ok";
    case DecodeStatus::kBadLength: return "bad length";
    case DecodeStatus::kBadMagic: return "bad magic";
    case DecodeStatus::kBadVersion: return "bad version";
    case DecodeStatus::kBadType: return "bad type";
    case DecodeStatus::kBadChecksum: return "bad checksum";
    case DecodeStatus::kNonFinite: return "non-finite value";
  }
  return "unknown";
}

std::uint32_t Crc32(const std::uint8_t* data, std::size_t size) {
  return std::uint32_t(crc32(crc32(0L, Z_NULL, 0), data, uInt(size)));
}

void EncodePose(const PosePacket& p, PoseBytes* out) {
  std::uint8_t* b = out->data();
  std::size_t at = 0;
  Put(b, &at, kPoseMagic);
  Put(b, &at, kVersion);
  Put(b, &at, kTypePose);
  Put(b, &at, p.sequence);
  Put(b, &at, p.timestamp_ns);
  for (double v : p.position) Put(b, &at, v);
  for (double v : p.quaternion) Put(b, &at, v);
  Put(b, &at, p.buttons);
  Put(b, &at, Crc32(b, at));
}

void EncodeWrench(const WrenchPacket& w, WrenchBytes* out) {
  std::uint8_t* b = out->data();
  std::size_t at = 0;
  Put(b, &at, kWrenchMagic);
  Put(b, &at, kVersion);
  Put(b, &at, kTypeWrench);
  Put(b, &at, w.sequence);
  Put(b, &at, w.timestamp_ns);
  for (double v : w.force) Put(b, &at, v);
  for (double v : w.torque) Put(b, &at, v);
  Put(b, &at, w.pose_sequence);
  Put(b, &at, w.flags);
  Put(b, &at, Crc32(b, at));
}

DecodeStatus DecodePose(const std::uint8_t* d, std::size_t size, PosePacket* out) {
  const DecodeStatus s = CheckHeader(d, size, kPosePacketSize, kPoseMagic, kTypePose);
  if (s != DecodeStatus::kOk) return s;
  PosePacket p;
  std::size_t at = 8;
  p.sequence = Get<std::uint64_t>(d, &at);
  p.timestamp_ns = Get<std::int64_t>(d, &at);
  for (double& v : p.position) v = Get<double>(d, &at);
  for (double& v : p.quaternion) v = Get<double>(d, &at);
  p.buttons = Get<std::uint32_t>(d, &at);
  if (!IsUsableDevicePose(p.position, p.quaternion)) return DecodeStatus::kNonFinite;
  *out = p;
  return DecodeStatus::kOk;
}

DecodeStatus DecodeWrench(const std::uint8_t* d, std::size_t size, WrenchPacket* out) {
  const DecodeStatus s = CheckHeader(d, size, kWrenchPacketSize, kWrenchMagic, kTypeWrench);
  if (s != DecodeStatus::kOk) return s;
  WrenchPacket w;
  std::size_t at = 8;
  w.sequence = Get<std::uint64_t>(d, &at);
  w.timestamp_ns = Get<std::int64_t>(d, &at);
  bool finite = true;
  for (double& v : w.force) finite = finite && std::isfinite(v = Get<double>(d, &at));
  for (double& v : w.torque) finite = finite && std::isfinite(v = Get<double>(d, &at));
  w.pose_sequence = Get<std::uint64_t>(d, &at);
  w.flags = Get<std::uint32_t>(d, &at);
  if (!finite) return DecodeStatus::kNonFinite;
  *out = w;
  return DecodeStatus::kOk;
}

}  // namespace contactlab::udp
