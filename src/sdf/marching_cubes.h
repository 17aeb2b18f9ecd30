// Marching cubes on a distance-field grid (Barbič & James 2008, sec. 2.3: the soup pipeline
// extracts the isosurface of the unsigned field at a small offset).
//
// The case table (256 cases) is generated once from a face rule instead of being written out:
// on each cube face the edge crossings are joined so that every inside corner (value < iso) is
// cut off on its own (ambiguous faces separate inside corners). Two cubes sharing a face see
// the same corner values and so make the same cuts; with one vertex per crossed grid edge the
// output is therefore closed and edge-manifold (polygons are split by fans whose diagonals
// stay off the cube faces, or around a centroid vertex) wherever the grid's boundary samples are
// >= iso, and consistently oriented.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "sdf/field_grid.h"

namespace contactlab {

// Polygons of case MASK (bit c set: corner c = x + 2y + 4z is inside), oriented to face the
// outside, as records [n, fan, e_0 .. e_{n-1}] of cube-edge indices, terminated by -1. FAN is
// the polygon vertex to fan-triangulate from, or -1 when every fan would put a diagonal on a
// cube face (a neighbour might use the same diagonal): such polygons are triangulated around
// their centroid. Edge e joins corners kCubeEdgeCorners[e].
inline constexpr int kMarchingCubesRow = 21;
const std::array<std::array<std::int8_t, kMarchingCubesRow>, 256>& MarchingCubesTable();
inline constexpr std::int8_t kCubeEdgeCorners[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                                        {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// The isosurface {value == ISO} of the grid samples VALUES (GRID.num_points(), x fastest),
// separating samples < ISO ("inside") from the others; triangles face the >= ISO side. One
// vertex per crossed grid edge, linearly interpolated. CLOSE_AT_BOUNDARY treats samples beyond
// the grid as >= ISO, so the surface is always closed. The mesh is named NAME.
TriangleMesh ExtractIsosurface(const std::vector<float>& values, const FieldGrid& grid, double iso,
                               bool close_at_boundary = false, const std::string& name = "isosurface");

}  // namespace contactlab
