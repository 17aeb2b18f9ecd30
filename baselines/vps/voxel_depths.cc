// The distance-layered voxmap (Sagardia, Hulin et al., DLR): depth in voxel layers and normal
// of every contact voxel, from the static body's signed distance field.
#include "baselines/vps/voxel_depths.h"

#include <algorithm>

namespace contactlab {

std::uint16_t VoxelDepthMap::EncodeNormal(const Eigen::Vector3d& n) {
  // Project onto the octahedron |x| + |y| + |z| = 1 and fold its lower half over the upper.
  const double l1 = std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z());
  double x = n.x() / l1, y = n.y() / l1;
  if (n.z() < 0) {
    const double ox = x;
    x = (1 - std::abs(y)) * (ox >= 0 ? 1 : -1);
    y = (1 - std::abs(ox)) * (y >= 0 ? 1 : -1);
  }
  // 255 levels, 127 the zero: axis-aligned normals are exact.
  auto quantise = [](double t) { return unsigned(std::lround(std::clamp(t, -1.0, 1.0) * 127) + 127); };
  return std::uint16_t(quantise(x) | (quantise(y) << 8));
}

VoxelDepthMap BuildVoxelDepthMap(const DistanceField& field, const Voxmap& voxmap) {
  VoxelDepthMap map;
  map.entries_.assign(std::size_t(voxmap.num_voxels()), VoxelDepth{kNoDepth, 0});
  const Eigen::Vector3i n = voxmap.dims();
  const double steps_per_metre = kDepthSteps / voxmap.voxel_size();
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const std::int64_t idx = voxmap.Index(i, j, k);
        const VoxelClass c = voxmap.Get(idx);
        if (c != VoxelClass::kSurface && c != VoxelClass::kInterior) continue;
        // Depth and outward normal of B at the voxel's centre.
        Eigen::Vector3d g;
        const double d = field.DistanceAndGradient(voxmap.Centre(i, j, k), &g);
        const double gn = g.norm();
        if (!(gn > 1e-6) || !std::isfinite(d)) continue;  // on the medial axis: no direction
        const double steps = std::clamp(std::round(-d * steps_per_metre), -32767.0, 32767.0);
        map.entries_[std::size_t(idx)] = {std::int16_t(steps), VoxelDepthMap::EncodeNormal(g / gn)};
      }
  return map;
}

}  // namespace contactlab
