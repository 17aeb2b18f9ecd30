// Unsigned distance from a triangle set sampled on a grid (Barbič & James 2008, sec. 2.3):
// exact point-triangle distances in a narrow band around every triangle, then closest-triangle
// propagation (Bridson-style) to the rest of the grid.
//
// What is exact and what is approximate:
//  * every sample is the exact distance (double arithmetic, stored as float) from its grid
//    point to ONE triangle of the mesh, so it never underestimates the true distance;
//  * every grid point whose true distance is <= band_voxels * spacing holds the exact distance
//    to the mesh (its closest triangle's bounding box, grown by the band, contains the point,
//    so that triangle was tested);
//  * farther points hold the distance to the best triangle found by propagating closest-
//    triangle ids along the grid axes (three rounds of forward/backward passes along x, y, z);
//    this is an upper bound, in practice within a fraction of a voxel of the truth (largest
//    near medial surfaces of finely tessellated curved parts, whose closest-triangle regions
//    are thinner than a voxel);
//  * the samples on the grid's six boundary faces are exact again (BVH queries), because the
//    field's outside-the-box bound is built on their minimum.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "sdf/field_grid.h"

namespace contactlab {

struct UnsignedDistanceGrid {
  std::vector<float> distance;                // grid.num_points() samples, metres, x fastest
  std::vector<std::int32_t> closest_triangle;  // triangle index behind each sample
};

// Triangle corners as one flat array: 9 doubles per triangle (a, b, c), metres.
std::vector<double> FlattenTriangles(const TriangleMesh& mesh);

// Unsigned distance from every point of GRID to MESH (at least one triangle; indices valid).
// BAND_VOXELS >= 1 sets the exact band. Parallel (TBB); SHOW_PROGRESS draws on a terminal.
UnsignedDistanceGrid ComputeUnsignedDistance(const TriangleMesh& mesh, const FieldGrid& grid,
                                             int band_voxels = 3, bool show_progress = false);

}  // namespace contactlab
