// Inside/outside of grid points for a closed triangle mesh (Barbič & James 2008, sec. 2.3: the
// sign of the distance field), by signed ray crossings along grid lines in x, y and z with a
// majority vote.
//
// Along each grid line the signed crossings (+1/-1 by the triangle's facing) are summed in
// order; a point is inside along that axis when the sum before it (its winding number) is
// non-zero. Point-in-triangle tests in the projection use a top-left tie rule on edge
// functions evaluated in a canonical vertex order, so a line through a shared edge or vertex
// is counted consistently by the triangles around it. Three axes vote; two votes decide.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "sdf/field_grid.h"

namespace contactlab {

// One byte per grid point (x fastest): 1 inside MESH, 0 outside. MESH should be closed
// (watertight); orientation does not matter (non-zero winding rule). Parallel (TBB).
std::vector<std::uint8_t> ClassifyInsideByRayCrossings(const TriangleMesh& mesh, const FieldGrid& grid,
                                                       bool show_progress = false);

}  // namespace contactlab
