// Connected components of a surface and removal of those enclosed by others (Barbič & James
// 2008, sec. 2.3: after extracting the offset isosurface of a polygon soup, components that lie
// inside other components, such as the inner sheet of a thin closed region, are dropped).
#pragma once

#include <vector>

#include "geometry/triangle_mesh.h"

namespace contactlab {

// Connected components of MESH by shared vertex indices, each with its own compact vertex
// list, in order of their first triangle. Names are MESH.name + " component N".
std::vector<TriangleMesh> SplitComponents(const TriangleMesh& mesh);

// The components of MESH (closed surfaces) that are not enclosed by another component: C is
// enclosed by D when C's bounding box lies in D's and D's winding number at a vertex of C has
// magnitude > 1/2. Returns their union (named after MESH); REMOVED receives the count dropped.
TriangleMesh RemoveEnclosedComponents(const TriangleMesh& mesh, int* removed = nullptr);

}  // namespace contactlab
