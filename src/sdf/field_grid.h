// The sampling grid of a distance field (Barbič & James 2008, sec. 2.3): the mesh bounding
// box padded on each side, cubic voxels, a given number of cells along the longest side.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "geometry/aabb.h"

namespace contactlab {

struct FieldGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // grid point (0,0,0), metres
  double spacing = 1;                                // voxel edge, metres
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();    // grid points per axis (cells + 1)

  std::int64_t num_points() const { return std::int64_t(dims.x()) * dims.y() * dims.z(); }
  std::int64_t Index(int i, int j, int k) const {
    return i + std::int64_t(dims.x()) * (j + std::int64_t(dims.y()) * k);
  }
  Eigen::Vector3d Point(int i, int j, int k) const { return origin + spacing * Eigen::Vector3d(i, j, k); }
};

// The grid for BOUNDS (non-empty): the box grows by PADDING * largest extent on every side;
// RESOLUTION cells span the longest side of the padded box; the other sides get the fewest
// whole cells that cover them (at least 1), centred on the padded box. A flat or point-like
// box gets a minimal extent so that the spacing stays positive.
FieldGrid MakeFieldGrid(const Aabb& bounds, int resolution, double padding);

}  // namespace contactlab
