// McNeely, Puterbaugh & Troy 1999, sec. 4.1: the 2-bit voxmap, classified from a distance field.
#include "baselines/vps/voxmap.h"

#include <cmath>
#include <string>

#include "util/error.h"

namespace contactlab {

Voxmap::Voxmap(const Eigen::Vector3d& origin, double voxel_size, const Eigen::Vector3i& dims)
    : origin_(origin), voxel_size_(voxel_size), dims_(dims) {
  if (!(voxel_size > 0) || !std::isfinite(voxel_size)) Fail("voxmap", "the voxel size must be finite and positive");
  if ((dims.array() < 1).any()) Fail("voxmap", "every dimension must hold at least one voxel");
  bits_.assign(std::size_t((num_voxels() + 3) / 4), 0);  // all free (class 0)
  counts_[int(VoxelClass::kFree)] = num_voxels();
  ox_ = float(origin.x());
  oy_ = float(origin.y());
  oz_ = float(origin.z());
  inv_v_ = float(1.0 / voxel_size);
}

void Voxmap::Set(std::int64_t index, VoxelClass c) {
  const VoxelClass old = Get(index);
  std::uint8_t& byte = bits_[std::size_t(index >> 2)];
  const int shift = int(2 * (index & 3));
  byte = std::uint8_t((byte & ~(3u << shift)) | (unsigned(c) << shift));
  --counts_[int(old)];
  ++counts_[int(c)];
}

Voxmap BuildVoxmap(const DistanceField& field, const VoxmapOptions& options) {
  const std::string where =
      "voxmap of " + (field.info().source.empty() ? std::string("distance field") : field.info().source);
  if (field.empty()) Fail(where, "the distance field is empty");
  if (!std::isfinite(options.voxel_size)) Fail(where, "the voxel size is not finite");
  const double v = options.voxel_size > 0 ? options.voxel_size : field.spacing();
  if (!(v > 0) || !std::isfinite(v)) Fail(where, "the voxel size must be finite and positive");
  // Enough voxels to cover the box; the small tolerance keeps v == spacing at dims - 1.
  const Eigen::Vector3d size = field.box().size();
  Eigen::Vector3i n;
  double total = 1;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil(size[a] / v - 1e-6);
    if (!(cells < 2e9)) Fail(where, "voxel size " + std::to_string(v) + " m gives too many voxels");
    n[a] = std::max(1, int(cells));
    total *= n[a];
  }
  if (total > double(options.max_voxels)) {
    Fail(where, "voxel size " + std::to_string(v) + " m gives " + std::to_string(std::int64_t(total)) +
                    " voxels, more than the limit of " + std::to_string(options.max_voxels));
  }
  Voxmap map(field.box().min, v, n);

  // Classes before packing (one byte per voxel): surface and interior from the field values.
  std::vector<std::uint8_t> cls(std::size_t(map.num_voxels()), std::uint8_t(VoxelClass::kFree));
  const int cx = n.x() + 1, cy = n.y() + 1;
  std::vector<float> corner(std::size_t(cx) * cy * 2);  // two corner layers, k and k + 1
  auto corner_at = [&](int i, int j, int layer) -> float& {
    return corner[std::size_t(i) + std::size_t(cx) * (std::size_t(j) + std::size_t(cy) * layer)];
  };
  const Eigen::Vector3d& o = map.origin();
  for (int j = 0; j < cy; ++j)
    for (int i = 0; i < cx; ++i) corner_at(i, j, 0) = float(field.Distance(o + v * Eigen::Vector3d(i, j, 0)));
  for (int k = 0; k < n.z(); ++k) {
    const int lo_layer = k & 1, hi_layer = lo_layer ^ 1;
    for (int j = 0; j < cy; ++j)
      for (int i = 0; i < cx; ++i) corner_at(i, j, hi_layer) = float(field.Distance(o + v * Eigen::Vector3d(i, j, k + 1)));
    for (int j = 0; j < n.y(); ++j) {
      for (int i = 0; i < n.x(); ++i) {
        float lo = INFINITY, hi = -INFINITY;
        for (int c = 0; c < 8; ++c) {
          const float d = corner_at(i + (c & 1), j + ((c >> 1) & 1), (c & 4) ? hi_layer : lo_layer);
          lo = std::min(lo, d);
          hi = std::max(hi, d);
        }
        // The plane through the nearest surface point, perpendicular to the gradient g,
        // crosses the voxel iff |d(c)| <= (v / 2) |g / |g||_1 (the voxel's half-width along g).
        Eigen::Vector3d g;
        const double dc = field.DistanceAndGradient(map.Centre(i, j, k), &g);
        const double gn = g.norm();
        const double reach = 0.5 * v * (gn > 0 ? g.cwiseAbs().sum() / gn : std::sqrt(3.0));
        VoxelClass c = VoxelClass::kFree;
        if ((lo <= 0.f && 0.f <= hi && lo < hi) || std::abs(dc) <= reach) {
          c = VoxelClass::kSurface;
        } else if (dc < 0) {
          c = VoxelClass::kInterior;
        }
        cls[std::size_t(map.Index(i, j, k))] = std::uint8_t(c);
      }
    }
  }

  // Proximity: non-contact voxels with a contact voxel among their 26 neighbours.
  auto is_contact = [&](std::int64_t idx) {
    return cls[std::size_t(idx)] == std::uint8_t(VoxelClass::kSurface) ||
           cls[std::size_t(idx)] == std::uint8_t(VoxelClass::kInterior);
  };
  std::vector<std::uint8_t> proximity(cls.size(), 0);
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        if (!is_contact(map.Index(i, j, k))) continue;
        for (int dk = std::max(0, k - 1); dk <= std::min(n.z() - 1, k + 1); ++dk)
          for (int dj = std::max(0, j - 1); dj <= std::min(n.y() - 1, j + 1); ++dj)
            for (int di = std::max(0, i - 1); di <= std::min(n.x() - 1, i + 1); ++di) {
              const std::int64_t m = map.Index(di, dj, dk);
              if (!is_contact(m)) proximity[std::size_t(m)] = 1;
            }
      }

  // Pack.
  for (std::int64_t idx = 0; idx < map.num_voxels(); ++idx) {
    const VoxelClass c = proximity[std::size_t(idx)] ? VoxelClass::kProximity : VoxelClass(cls[std::size_t(idx)]);
    if (c != VoxelClass::kFree) map.Set(idx, c);
  }
  return map;
}

}  // namespace contactlab
