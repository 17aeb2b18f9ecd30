// The voxmap of Voxmap-PointShell (McNeely, Puterbaugh & Troy 1999, sec. 4.1): the static
// body's voxels classified free / proximity / surface / interior, 2 bits per voxel, 4 per byte.
// Built here from the body's signed distance field instead of from its triangles.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sdf/distance_field.h"

namespace contactlab {

// The 2-bit voxel states (values as stored).
enum class VoxelClass : std::uint8_t {
  kFree = 0,       // neither touching nor next to the surface
  kProximity = 1,  // free, but 26-adjacent to a surface or interior voxel
  kSurface = 2,    // the zero level set passes through the voxel
  kInterior = 3,   // wholly inside the body
};

struct VoxmapOptions {
  // Voxel side, metres; <= 0 (default) uses the field's grid spacing.
  double voxel_size = 0;
  // Largest number of voxels accepted (a guard against a tiny voxel size exhausting memory).
  std::int64_t max_voxels = std::int64_t(1) << 31;
};

// Voxel (i, j, k) is the closed-open box ORIGIN + voxel_size * ([i, i+1) x [j, j+1) x [k, k+1)),
// in the field body's frame. Voxels are stored x fastest, 4 per byte, voxel n in bits
// 2 (n mod 4) .. 2 (n mod 4) + 1 of byte n / 4. Everything outside the grid is free.
class Voxmap {
 public:
  Voxmap() = default;
  // An all-free voxmap of DIMS voxels (each >= 1) of side VOXEL_SIZE > 0 from ORIGIN.
  Voxmap(const Eigen::Vector3d& origin, double voxel_size, const Eigen::Vector3i& dims);

  const Eigen::Vector3d& origin() const { return origin_; }
  double voxel_size() const { return voxel_size_; }
  const Eigen::Vector3i& dims() const { return dims_; }
  std::int64_t num_voxels() const { return std::int64_t(dims_.x()) * dims_.y() * dims_.z(); }
  // Bytes of voxel storage: ceil(num_voxels / 4).
  std::size_t memory_bytes() const { return bits_.size(); }
  // Number of voxels of each class, indexed by VoxelClass value.
  std::int64_t count(VoxelClass c) const { return counts_[int(c)]; }

  std::int64_t Index(int i, int j, int k) const {
    return i + std::int64_t(dims_.x()) * (j + std::int64_t(dims_.y()) * k);
  }
  Eigen::Vector3d Centre(int i, int j, int k) const {
    return origin_ + voxel_size_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
  }
  VoxelClass Get(std::int64_t index) const {
    return VoxelClass((bits_[std::size_t(index >> 2)] >> (2 * (index & 3))) & 3u);
  }
  VoxelClass Get(int i, int j, int k) const { return Get(Index(i, j, k)); }
  // Sets voxel INDEX (0 <= INDEX < num_voxels) and keeps the class counts.
  void Set(std::int64_t index, VoxelClass c);

  // Voxel containing P (field-body frame, metres): its class and, when P is inside the grid,
  // its indices in *I, *J, *K. Outside the grid (or P not finite): kFree and false.
  // Inline, allocation-free, for the haptic loop.
  inline bool Locate(float x, float y, float z, int* i, int* j, int* k) const;

 private:
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double voxel_size_ = 1;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<std::uint8_t> bits_;  // (ceil(#voxels / 4)) packed 2-bit classes
  std::int64_t counts_[4] = {0, 0, 0, 0};
  // Hot-path copies in float.
  float ox_ = 0, oy_ = 0, oz_ = 0, inv_v_ = 1;
};

// Classifies the voxels of a grid laid over FIELD's box (same lower corner; enough voxels per
// axis to cover it) from the field's trilinear values at the 8 voxel corners and the centre c:
//   surface   the zero level set passes through the voxel: the corner values change sign
//             (min <= 0 <= max, min < max), or the surface's tangent plane at the nearest
//             surface point crosses the voxel: |d(c)| <= (v / 2) |g|_1 / |g|_2 with g the
//             field gradient at c (between the inscribed radius v / 2 for an axis-aligned
//             surface and half the diagonal v sqrt(3) / 2 for a diagonal one; exact for a
//             plane). Not simply |d(c)| <= half the diagonal: for an axis-aligned face that
//             also marks a whole layer of voxels the surface misses;
//   interior  not surface and d(c) < 0;
//   proximity not surface nor interior, and 26-adjacent to a surface or interior voxel;
//   free      the rest.
// Throws Error naming FIELD's source for an empty field, a voxel size that is not finite, or
// more than options.max_voxels voxels.
Voxmap BuildVoxmap(const DistanceField& field, const VoxmapOptions& options = {});

inline bool Voxmap::Locate(float x, float y, float z, int* i, int* j, int* k) const {
  const float gx = (x - ox_) * inv_v_, gy = (y - oy_) * inv_v_, gz = (z - oz_) * inv_v_;
  if (!(gx >= 0.f && gy >= 0.f && gz >= 0.f && gx < float(dims_.x()) && gy < float(dims_.y()) &&
        gz < float(dims_.z()))) {
    return false;
  }
  // The float comparison can admit gx == dims after rounding; clamp to the last voxel.
  *i = std::min(int(gx), dims_.x() - 1);
  *j = std::min(int(gy), dims_.y() - 1);
  *k = std::min(int(gz), dims_.z() - 1);
  return true;
}

}  // namespace contactlab
