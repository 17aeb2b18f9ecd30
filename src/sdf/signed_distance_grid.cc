// The closed pipeline: unsigned distance with ray-crossing sign (Barbič & James 2008, sec. 2.3).
#include "sdf/signed_distance_grid.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "sdf/ray_crossing_sign.h"
#include "sdf/unsigned_distance_grid.h"

namespace contactlab {

std::vector<float> ComputeSignedDistance(const TriangleMesh& mesh, const FieldGrid& grid, int band_voxels,
                                         bool show_progress) {
  UnsignedDistanceGrid u = ComputeUnsignedDistance(mesh, grid, band_voxels, show_progress);
  u.closest_triangle = {};
  const std::vector<std::uint8_t> inside = ClassifyInsideByRayCrossings(mesh, grid, show_progress);
  std::vector<float>& d = u.distance;
  tbb::parallel_for(std::int64_t(0), std::int64_t(d.size()), std::int64_t(1 << 16), [&](std::int64_t b) {
    const std::int64_t e = std::min<std::int64_t>(b + (1 << 16), d.size());
    for (std::int64_t n = b; n < e; ++n) {
      if (inside[n]) d[n] = -d[n];
    }
  });
  // Conservative boundary minimum (see the header).
  std::int64_t arg = -1;
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const bool face = k == 0 || k == nz - 1 || j == 0 || j == ny - 1;
      for (int i = 0; i < nx; i += face ? 1 : std::max(1, nx - 1)) {
        const std::int64_t idx = grid.Index(i, j, k);
        if (arg < 0 || d[idx] < d[arg]) arg = idx;
      }
    }
  const double h = grid.spacing, m = d[arg];
  if (m > 0) d[arg] = float(std::sqrt(std::max(0.0, m * m - h * h / 2)));
  return std::move(u.distance);
}

}  // namespace contactlab
