// McNeely, Puterbaugh & Troy 1999, sec. 4.2: the surface-voxel-centre pointshell, and its
// projection onto the surface (DLR's VPS).
#include "baselines/vps/vps_pointshell.h"

#include <cmath>
#include <string>

#include "pointshell/build_pointshell.h"
#include "pointshell/level_set_sampling.h"
#include "util/error.h"

namespace contactlab {

Pointshell BuildVpsPointshell(const DistanceField& field, double voxel_size, std::uint64_t seed) {
  if (!(voxel_size > 0) || !std::isfinite(voxel_size)) {
    Fail("VPS pointshell of " + (field.info().source.empty() ? std::string("distance field") : field.info().source),
         "the voxel size must be finite and positive (got " + std::to_string(voxel_size) + ")");
  }
  PointshellOptions o;
  o.method = PointshellMethod::kVoxel;
  o.voxel_size = voxel_size;
  o.offset = 0.0;
  o.num_levels = 1;
  o.seed = seed;
  o.show_progress = false;
  return BuildPointshell(field, o);
}

void ProjectVpsPointshellOntoSurface(const DistanceField& field, Pointshell* shell) {
  const double tolerance = LevelSetTolerance(field);
  for (int i = 0; i < shell->num_points(); ++i) {
    Eigen::Vector3d p(shell->x[i], shell->y[i], shell->z[i]), g;
    if (!ProjectOntoLevelSet(field, 0.0, tolerance, 32, &p, &g)) continue;
    const double len = g.norm();
    if (!(len > 0)) continue;
    shell->x[i] = float(p.x());
    shell->y[i] = float(p.y());
    shell->z[i] = float(p.z());
    shell->nx[i] = float(-g.x() / len);
    shell->ny[i] = float(-g.y() / len);
    shell->nz[i] = float(-g.z() / len);
  }
}

}  // namespace contactlab
