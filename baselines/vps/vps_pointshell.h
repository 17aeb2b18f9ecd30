// The VPS pointshell (McNeely, Puterbaugh & Troy 1999, sec. 4.2): the centres of the moving
// body's surface voxels, each with the surface's inward normal; or, as DLR's VPS samples it
// (Sagardia, Hulin et al.), those centres projected onto the surface.
#pragma once

#include <cstdint>

#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

// Points at the centres of the voxels of side VOXEL_SIZE (metres, > 0; grid from FIELD's box
// corner) that the zero level set of FIELD (body A's distance field) crosses, with inward unit
// normals -grad d / |grad d| at the centres (BuildPointshell with PointshellMethod::kVoxel,
// offset 0, one level, order shuffled by SEED). Throws Error naming the field's source for a
// non-positive voxel size, a field with no zero crossing, or a vanishing gradient.
Pointshell BuildVpsPointshell(const DistanceField& field, double voxel_size, std::uint64_t seed = 1);

// Moves every point of SHELL (built on FIELD's zero level set, one level) onto that level set
// by Newton steps along the field's gradient and sets its inward normal there; a point whose
// projection fails (vanishing gradient) keeps its place and normal. A voxel centre lies up to
// half a voxel diagonal off the surface, so the projected points touch when the surface does.
void ProjectVpsPointshellOntoSurface(const DistanceField& field, Pointshell* shell);

}  // namespace contactlab
