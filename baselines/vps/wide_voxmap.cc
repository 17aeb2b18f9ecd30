// McNeely, Puterbaugh & Troy 2006, sec. 3: the 8-bit voxmap whose free voxels hold their
// distance to the nearest contact voxel, by a breadth-first distance transform.
#include "baselines/vps/wide_voxmap.h"

#include <algorithm>

namespace contactlab {

WideVoxmap BuildWideVoxmap(const Voxmap& voxmap) {
  WideVoxmap wide;
  wide.origin_ = voxmap.origin();
  wide.voxel_size_ = voxmap.voxel_size();
  wide.dims_ = voxmap.dims();
  const std::int64_t total = voxmap.num_voxels();
  wide.values_.assign(std::size_t(total), kWideMaxLayer);

  // Sources: every contact voxel (surface 0, interior 255), in index order.
  std::vector<std::int64_t> frontier, next;
  for (std::int64_t idx = 0; idx < total; ++idx) {
    const VoxelClass c = voxmap.Get(idx);
    if (c == VoxelClass::kSurface) {
      wide.values_[std::size_t(idx)] = kWideSurface;
      frontier.push_back(idx);
    } else if (c == VoxelClass::kInterior) {
      wide.values_[std::size_t(idx)] = kWideInterior;
      frontier.push_back(idx);
    }
  }
  // Layer by layer over the 26-neighbourhood; a free voxel takes the first layer reaching it.
  std::vector<std::uint8_t> done(std::size_t(total), 0);
  for (std::int64_t idx : frontier) done[std::size_t(idx)] = 1;
  const Eigen::Vector3i n = voxmap.dims();
  const std::int64_t nx = n.x(), nxy = std::int64_t(n.x()) * n.y();
  for (int layer = 1; layer < kWideMaxLayer && !frontier.empty(); ++layer) {
    next.clear();
    for (std::int64_t idx : frontier) {
      const int k = int(idx / nxy), j = int((idx % nxy) / nx), i = int(idx % nx);
      for (int dk = std::max(0, k - 1); dk <= std::min(n.z() - 1, k + 1); ++dk)
        for (int dj = std::max(0, j - 1); dj <= std::min(n.y() - 1, j + 1); ++dj)
          for (int di = std::max(0, i - 1); di <= std::min(n.x() - 1, i + 1); ++di) {
            const std::int64_t m = voxmap.Index(di, dj, dk);
            if (done[std::size_t(m)]) continue;
            done[std::size_t(m)] = 1;
            wide.values_[std::size_t(m)] = std::uint8_t(layer);
            next.push_back(m);
          }
    }
    frontier.swap(next);
  }
  return wide;
}

}  // namespace contactlab
