// The binary UDP packets between ContactLab and a networked haptic device (Barbič & James 2008,
// sec. 5: manipulandum pose in, coupling wrench out). Format documented in UDP_PROTOCOL.md:
// little-endian, fixed 88-byte packets, CRC-32 (IEEE, as zlib's crc32) over all bytes before it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace contactlab::udp {

inline constexpr std::uint32_t kPoseMagic = 0x31504C43;    // bytes "CLP1"
inline constexpr std::uint32_t kWrenchMagic = 0x31574C43;  // bytes "CLW1"
inline constexpr std::uint16_t kVersion = 1;
inline constexpr std::uint16_t kTypePose = 1;
inline constexpr std::uint16_t kTypeWrench = 2;
inline constexpr std::size_t kPosePacketSize = 88;
inline constexpr std::size_t kWrenchPacketSize = 88;

// Device -> ContactLab: one pose sample.
struct PosePacket {
  std::uint64_t sequence = 0;     // strictly increasing per sender
  std::int64_t timestamp_ns = 0;  // sender's clock, ns
  double position[3] = {0, 0, 0}; // metres
  double quaternion[4] = {1, 0, 0, 0};  // w, x, y, z (normalised by the receiver)
  std::uint32_t buttons = 0;      // bit i = button i
};

// ContactLab -> device: the wrench to hold until the next packet.
struct WrenchPacket {
  std::uint64_t sequence = 0;       // strictly increasing per sender
  std::int64_t timestamp_ns = 0;    // sender's (haptic loop) clock, ns
  double force[3] = {0, 0, 0};      // N, world = device frame
  double torque[3] = {0, 0, 0};     // N m
  std::uint64_t pose_sequence = 0;  // sequence of the newest pose packet acted on
  std::uint32_t flags = 0;          // SafetyFlag bits of this cycle (safety_filter.h)
};

enum class DecodeStatus {
  kOk,
  kBadLength,     // datagram length differs from the packet size (short or long)
  kBadMagic,
  kBadVersion,
  kBadType,
  kBadChecksum,
  kNonFinite,     // a non-finite number, or a quaternion whose squared norm is ~0 or overflows
};
const char* ToString(DecodeStatus s);

using PoseBytes = std::array<std::uint8_t, kPosePacketSize>;
using WrenchBytes = std::array<std::uint8_t, kWrenchPacketSize>;

// Encoders fill the fixed buffers (checksum included). Decoders check length, magic, version,
// type, checksum and finiteness, in that order. None allocates or throws.
void EncodePose(const PosePacket& p, PoseBytes* out);
void EncodeWrench(const WrenchPacket& w, WrenchBytes* out);
DecodeStatus DecodePose(const std::uint8_t* data, std::size_t size, PosePacket* out);
DecodeStatus DecodeWrench(const std::uint8_t* data, std::size_t size, WrenchPacket* out);

// CRC-32 (IEEE 802.3, reflected, as zlib crc32) of SIZE bytes.
std::uint32_t Crc32(const std::uint8_t* data, std::size_t size);

}  // namespace contactlab::udp
