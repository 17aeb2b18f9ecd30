// Mesh simplification by edge collapse (CGAL Surface_mesh_simplification, Lindstrom-Turk cost
// and placement), used to thin large meshes for display in the viewer. Built with CGAL only
// (CONTACTLAB_HAVE_CGAL; GPL-3.0-or-later).
#pragma once

#include <string>

#include "geometry/triangle_mesh.h"

namespace contactlab {

// MESH (a soup is made a polygon mesh first, as the CGAL references do) with edges collapsed,
// cheapest first, until it has at most MAX_TRIANGLES triangles (a few fewer: the stop counts
// edges, 3/2 per triangle). Returns MESH itself when it has no more than MAX_TRIANGLES. Throws
// Error naming WHERE when MESH is empty or MAX_TRIANGLES < 4.
TriangleMesh SimplifyMesh(const TriangleMesh& mesh, int max_triangles, const std::string& where);

}  // namespace contactlab
