// A uniform grid (cell list) for fixed-radius neighbour search in particle repulsion
// (Barbič & James 2008, sec. 2.4). Points are counting-sorted by row of cells (fixed j, k;
// a dense row table over the points' bounding box), then by cell i within the row, so the
// cells of a row that a query ball cuts are one contiguous range found by binary search.
// Memory and rebuild time grow with the points and the rows (a 2D table), not with the box
// volume; cells grow beyond the requested size when needed to keep the row count below
// kMaxCells (queries stay exact supersets).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <vector>

namespace contactlab {

class UniformGrid {
 public:
  static constexpr std::int64_t kMaxCells = std::int64_t(1) << 24;

  // One stored point: float position and its index in the caller's array.
  struct Entry {
    float x, y, z;
    std::int32_t index;
  };

  // Rebuilds the grid over POINTS[0, COUNT) with cubic cells of side at least CELL_SIZE
  // (metres, > 0). Stored indices are INDEX_OFFSET + i. Deterministic (by cell, then index).
  void Build(const Eigen::Vector3d* points, std::int32_t count, std::int32_t index_offset, double cell_size);

  // Calls VISIT(const Entry&) for every stored point in the cells that intersect the ball of
  // RADIUS (metres) around Q: a superset of the points within RADIUS of Q, in a fixed order.
  // Rows of cells (fixed j, k) are kept only when they come within RADIUS of Q, and each row
  // is cut to the chord of the ball, so small cells (side ~ RADIUS / 2) track the ball
  // closely. Never allocates.
  template <typename Visit>
  void ForEachNear(float qx, float qy, float qz, float radius, Visit&& visit) const {
    if (entries_.empty()) return;
    const float c = cell_;
    const float gy = (qy - oy_) * inv_cell_, gz = (qz - oz_) * inv_cell_, gr = radius * inv_cell_;
    const std::int64_t j0 = std::max<std::int64_t>(std::int64_t(std::floor(gy - gr)), 0);
    const std::int64_t j1 = std::min<std::int64_t>(std::int64_t(std::floor(gy + gr)), ny_ - 1);
    const std::int64_t k0 = std::max<std::int64_t>(std::int64_t(std::floor(gz - gr)), 0);
    const std::int64_t k1 = std::min<std::int64_t>(std::int64_t(std::floor(gz + gr)), nz_ - 1);
    const float r2 = radius * radius;
    for (std::int64_t k = k0; k <= k1; ++k) {
      // Distance from Q to the slab of cells k along z (0 inside).
      const float zlo = oz_ + float(k) * c, dz = std::max({zlo - qz, qz - (zlo + c), 0.f});
      for (std::int64_t j = j0; j <= j1; ++j) {
        const float ylo = oy_ + float(j) * c, dy = std::max({ylo - qy, qy - (ylo + c), 0.f});
        const float rest = r2 - dy * dy - dz * dz;
        if (rest < 0) continue;
        const float w = std::sqrt(rest);
        const std::int64_t i0 = std::max<std::int64_t>(std::int64_t(std::floor((qx - w - ox_) * inv_cell_)), 0);
        const std::int64_t i1 = std::min<std::int64_t>(std::int64_t(std::floor((qx + w - ox_) * inv_cell_)), nx_ - 1);
        if (i0 > i1) continue;
        const std::int64_t row = j + ny_ * k;
        const std::int32_t* first = entry_i_.data() + row_begin_[row];
        const std::int32_t* last = entry_i_.data() + row_begin_[row + 1];
        if (first == last) continue;
        const std::int32_t* b = std::lower_bound(first, last, std::int32_t(i0));
        const std::int32_t* e = std::upper_bound(b, last, std::int32_t(i1));
        for (const std::int32_t* it = b; it != e; ++it) visit(entries_[it - entry_i_.data()]);
      }
    }
  }

  std::int32_t size() const { return std::int32_t(entries_.size()); }

 private:
  float ox_ = 0, oy_ = 0, oz_ = 0, cell_ = 1, inv_cell_ = 1;
  std::int64_t nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<Entry> entries_;           // (#P) sorted by row, cell i, then index
  std::vector<std::int32_t> entry_i_;    // (#P) cell i of each entry (sorted within rows)
  std::vector<std::int32_t> row_begin_;  // (#rows + 1) entry range of each row (j + ny k)
  std::vector<std::int32_t> row_of_;     // (#P) scratch: row of each point, then its slot
  std::vector<std::int32_t> cell_i_;     // (#P) scratch: cell i of each point
  std::vector<std::int32_t> order_;      // (#P) scratch: point of each slot
};

}  // namespace contactlab
