// Grid layout of distance fields (Barbič & James 2008, sec. 2.3).
#include "sdf/field_grid.h"

#include <algorithm>
#include <cmath>

namespace contactlab {

FieldGrid MakeFieldGrid(const Aabb& bounds, int resolution, double padding) {
  const Eigen::Vector3d size = bounds.size();
  double extent = size.maxCoeff();
  if (!(extent > 0)) extent = std::max(1e-6, 1e-6 * bounds.max.cwiseAbs().maxCoeff());
  const Eigen::Vector3d lo = bounds.min.array() - padding * extent;
  const Eigen::Vector3d padded = size.array() + 2 * padding * extent;
  FieldGrid grid;
  grid.spacing = std::max(padded.maxCoeff(), extent) / resolution;
  for (int a = 0; a < 3; ++a) {
    const int cells = std::max(1, int(std::ceil(padded[a] / grid.spacing - 1e-9)));
    grid.dims[a] = cells + 1;
    // Centre the (slightly larger) grid on the padded box.
    grid.origin[a] = lo[a] - 0.5 * (cells * grid.spacing - padded[a]);
  }
  return grid;
}

}  // namespace contactlab
