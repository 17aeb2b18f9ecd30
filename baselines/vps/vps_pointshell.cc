// McNeely, Puterbaugh & Troy 1999, sec. 4.2: the surface-voxel-centre pointshell.
#include "baselines/vps/vps_pointshell.h"

#include <cmath>
#include <string>

#include "pointshell/build_pointshell.h"
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

}  // namespace contactlab
