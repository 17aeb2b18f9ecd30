// Signed distance samples of a closed triangle mesh on a grid (Barbič & James 2008, sec. 2.3,
// the "closed" pipeline): unsigned distance (narrow band exact + propagation, see
// unsigned_distance_grid.h) with the sign of ray-crossing votes (ray_crossing_sign.h).
#pragma once

#include <vector>

#include "geometry/triangle_mesh.h"
#include "sdf/field_grid.h"

namespace contactlab {

// The smallest boundary-face sample m is then lowered to sqrt(m^2 - h^2/2) (about
// m - h^2/(4m), a small fraction of a voxel with the default padding): between grid points the
// distance can dip below its sampled minimum by at most that much (at the continuous minimum
// D over the boundary the closest-point direction is normal to the face, so the nearest sample,
// at most h/sqrt(2) away in the face, is within sqrt(D^2 + h^2/2)). The field's
// outside-the-box bound d_box + d_boundary_min therefore never exceeds the true distance when
// the surface lies inside the grid box. This one sample is the only one that is not a distance.
//
// Samples (GRID.num_points(), x fastest, metres) of the signed distance to MESH, negative
// inside. MESH must be closed for the sign to mean anything; it must have a triangle.
std::vector<float> ComputeSignedDistance(const TriangleMesh& mesh, const FieldGrid& grid, int band_voxels = 3,
                                         bool show_progress = false);

}  // namespace contactlab
