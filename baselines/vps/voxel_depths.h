// The distance-layered voxmap of the VPS that DLR develops for virtual assembly (Sagardia,
// Hulin et al.; Sagardia's thesis, sec. 3.2.3, "enhanced voxelmaps"): beside its class, every
// contact voxel of the static body carries its distance to the surface in voxel layers and
// the surface's normal there, so a point deep inside is pushed back in proportion to its
// depth instead of by the surface layer's bounded amount (McNeely et al. 1999).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "baselines/vps/voxmap.h"
#include "sdf/distance_field.h"

namespace contactlab {

// One voxel's entry: the depth of its centre below B's surface and B's outward unit normal
// there, both from B's signed distance field d at the centre c (depth -d(c), normal
// grad d / |grad d|). 4 bytes, as one float of a field.
struct VoxelDepth {
  std::int16_t depth;    // -d(c) in 1/kDepthSteps voxel layers, saturated to +-32767
  std::uint16_t normal;  // octahedral encoding, 8 bits per coordinate (within about 1 degree)
};

// Depth steps per voxel layer: depths to 1/64 voxel, up to 511 layers deep.
inline constexpr int kDepthSteps = 64;
// The entry of a voxel that exerts no force: a free or proximity voxel, or a contact voxel
// whose centre sits where the field's gradient vanishes (the normal is undefined).
inline constexpr std::int16_t kNoDepth = INT16_MIN;

// Same grid as the Voxmap it is built from, one VoxelDepth per voxel, x fastest.
class VoxelDepthMap {
 public:
  VoxelDepthMap() = default;

  bool empty() const { return entries_.empty(); }
  std::int64_t num_voxels() const { return std::int64_t(entries_.size()); }
  std::size_t memory_bytes() const { return entries_.size() * sizeof(VoxelDepth); }
  const VoxelDepth& Get(std::int64_t index) const { return entries_[std::size_t(index)]; }

  // The depth of ENTRY's centre in voxel layers (ENTRY.depth != kNoDepth).
  static float DepthLayers(const VoxelDepth& entry) { return float(entry.depth) * (1.f / kDepthSteps); }
  // ENTRY's unit normal into N[3]. Allocation-free, for the haptic loop.
  static inline void Normal(const VoxelDepth& entry, float* n);
  // The octahedral code of the unit vector N (exposed for tests).
  static std::uint16_t EncodeNormal(const Eigen::Vector3d& n);

 private:
  friend VoxelDepthMap BuildVoxelDepthMap(const DistanceField& field, const Voxmap& voxmap);
  std::vector<VoxelDepth> entries_;  // (#voxels)
};

// The depth map of VOXMAP's surface and interior voxels from FIELD (the field VOXMAP was built
// from): at each such voxel's centre c, depth -d(c) in layers of VOXMAP's voxel size and the
// normal grad d / |grad d| of the trilinear field; kNoDepth elsewhere. Allocates #voxels
// entries.
VoxelDepthMap BuildVoxelDepthMap(const DistanceField& field, const Voxmap& voxmap);

inline void VoxelDepthMap::Normal(const VoxelDepth& entry, float* n) {
  // Octahedral decoding: the point of the octahedron |x| + |y| + |z| = 1, normalised.
  float x = (float(entry.normal & 0xffu) - 127.f) * (1.f / 127.f);
  float y = (float(entry.normal >> 8) - 127.f) * (1.f / 127.f);
  const float z = 1.f - std::abs(x) - std::abs(y);
  if (z < 0.f) {
    const float ox = x;
    x = (1.f - std::abs(y)) * (ox >= 0.f ? 1.f : -1.f);
    y = (1.f - std::abs(ox)) * (y >= 0.f ? 1.f : -1.f);
  }
  const float s = 1.f / std::sqrt(x * x + y * y + z * z);
  n[0] = x * s;
  n[1] = y * s;
  n[2] = z * s;
}

}  // namespace contactlab
