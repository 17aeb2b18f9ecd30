// The "wider" 8-bit voxmap of McNeely, Puterbaugh & Troy 2006 (Haptics-e, sec. 3): each free
// voxel stores its distance, in voxel layers, to the nearest voxel that can produce a contact
// force, so a point far from the static body is not looked at again for a number of cycles
// bounded by the maximum point speed (temporal coherence).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "baselines/vps/voxmap.h"

namespace contactlab {

// Voxel values of a WideVoxmap.
inline constexpr std::uint8_t kWideSurface = 0;     // surface voxel
inline constexpr std::uint8_t kWideProximity = 1;   // layer 1: 26-adjacent to a contact voxel
inline constexpr std::uint8_t kWideMaxLayer = 254;  // free voxels at >= 254 layers (capped)
inline constexpr std::uint8_t kWideInterior = 255;  // interior voxel

// Same grid as the Voxmap it is built from, one byte per voxel, x fastest. A free voxel's
// value n in 1..254 is its Chebyshev distance in voxels (26-neighbourhood BFS layers) to the
// nearest surface or interior ("contact") voxel, capped at 254; voxels from which no contact
// voxel is reachable get 254. Two voxel boxes n layers apart are at least (n - 1) voxel
// sizes apart, so a point in a layer-n voxel cannot reach a contact voxel before it has moved
// (n - 1) * voxel_size.
class WideVoxmap {
 public:
  WideVoxmap() = default;

  const Eigen::Vector3d& origin() const { return origin_; }
  double voxel_size() const { return voxel_size_; }
  const Eigen::Vector3i& dims() const { return dims_; }
  std::int64_t num_voxels() const { return std::int64_t(values_.size()); }
  // Bytes of voxel storage: num_voxels.
  std::size_t memory_bytes() const { return values_.size(); }
  std::int64_t Index(int i, int j, int k) const {
    return i + std::int64_t(dims_.x()) * (j + std::int64_t(dims_.y()) * k);
  }
  std::uint8_t Get(std::int64_t index) const { return values_[std::size_t(index)]; }
  std::uint8_t Get(int i, int j, int k) const { return values_[std::size_t(Index(i, j, k))]; }

 private:
  friend WideVoxmap BuildWideVoxmap(const Voxmap& voxmap);
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double voxel_size_ = 1;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<std::uint8_t> values_;  // (#voxels) layer, kWideSurface or kWideInterior
};

// The distance transform of VOXMAP's contact voxels (a multi-source breadth-first search over
// the 26-neighbourhood, stopped at 254 layers). Allocates a queue of up to #voxels indices.
WideVoxmap BuildWideVoxmap(const Voxmap& voxmap);

}  // namespace contactlab
