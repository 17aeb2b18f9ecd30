// Uniform grid cell list (Barbič & James 2008, sec. 2.4: neighbour search for repulsion).
#include "pointshell/uniform_grid.h"

#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <climits>

namespace contactlab {

void UniformGrid::Build(const Eigen::Vector3d* points, std::int32_t count, std::int32_t index_offset,
                        double cell_size) {
  entries_.resize(count);
  entry_i_.resize(count);
  if (count == 0) {
    row_begin_.assign(1, 0);
    nx_ = ny_ = nz_ = 0;
    return;
  }
  // Bounding box and cell size (grown if the box would need too many rows).
  Eigen::Vector3f lo = points[0].cast<float>(), hi = lo;
  for (std::int32_t i = 1; i < count; ++i) {
    const Eigen::Vector3f p = points[i].cast<float>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d extent = (hi - lo).cast<double>();
  double cell = cell_size;
  while ((std::floor(extent.y() / cell) + 1) * (std::floor(extent.z() / cell) + 1) > double(kMaxCells) ||
         std::floor(extent.x() / cell) + 1 > double(INT32_MAX / 2)) {
    cell *= 1.25;
  }
  ox_ = lo.x();
  oy_ = lo.y();
  oz_ = lo.z();
  cell_ = float(cell);
  inv_cell_ = float(1.0 / cell);
  nx_ = std::int64_t(std::floor(extent.x() * inv_cell_)) + 1;
  ny_ = std::int64_t(std::floor(extent.y() * inv_cell_)) + 1;
  nz_ = std::int64_t(std::floor(extent.z() * inv_cell_)) + 1;
  // Row and cell i of each point (parallel).
  row_of_.resize(count);
  cell_i_.resize(count);
  tbb::parallel_for(std::int32_t(0), count, [&](std::int32_t i) {
    const Eigen::Vector3f p = points[i].cast<float>();
    const std::int64_t ci = std::clamp<std::int64_t>(std::int64_t(std::floor((p.x() - ox_) * inv_cell_)), 0, nx_ - 1);
    const std::int64_t cj = std::clamp<std::int64_t>(std::int64_t(std::floor((p.y() - oy_) * inv_cell_)), 0, ny_ - 1);
    const std::int64_t ck = std::clamp<std::int64_t>(std::int64_t(std::floor((p.z() - oz_) * inv_cell_)), 0, nz_ - 1);
    row_of_[i] = std::int32_t(cj + ny_ * ck);
    cell_i_[i] = std::int32_t(ci);
  });
  // Stable counting sort by row (sequential: deterministic), O(#P + #rows).
  const std::size_t rows = std::size_t(ny_ * nz_);
  row_begin_.assign(rows + 1, 0);
  for (std::int32_t i = 0; i < count; ++i) ++row_begin_[row_of_[i] + 1];
  for (std::size_t r = 1; r <= rows; ++r) row_begin_[r] += row_begin_[r - 1];
  order_.resize(count);
  {
    std::vector<std::int32_t>& cursor = row_of_;  // becomes the slot of each point
    for (std::int32_t i = 0; i < count; ++i) {
      const std::int32_t slot = row_begin_[row_of_[i]]++;
      cursor[i] = slot;
      order_[slot] = i;
    }
  }
  for (std::size_t r = rows; r > 0; --r) row_begin_[r] = row_begin_[r - 1];
  row_begin_[0] = 0;
  // Within each row: by cell i, then point index (a total order: deterministic).
  tbb::parallel_for(std::size_t(0), rows, [&](std::size_t r) {
    const std::int32_t b = row_begin_[r], e = row_begin_[r + 1];
    if (e - b > 1) {
      std::sort(order_.begin() + b, order_.begin() + e, [&](std::int32_t u, std::int32_t v) {
        return cell_i_[u] != cell_i_[v] ? cell_i_[u] < cell_i_[v] : u < v;
      });
    }
  }, tbb::static_partitioner());
  tbb::parallel_for(std::int32_t(0), count, [&](std::int32_t slot) {
    const std::int32_t i = order_[slot];
    const Eigen::Vector3f p = points[i].cast<float>();
    entries_[slot] = {p.x(), p.y(), p.z(), index_offset + i};
    entry_i_[slot] = cell_i_[i];
  });
}

}  // namespace contactlab
