// The validation report of a triangle mesh: what holds (closed, manifold, oriented) and what
// does not. The distance-field builder picks its pipeline from it (closed or soup).
#pragma once

#include <string>

#include "geometry/aabb.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

struct MeshReport {
  int vertices = 0;
  int triangles = 0;
  int unreferenced_vertices = 0;
  int duplicate_vertices = 0;       // vertices at exactly the position of an earlier one
  int degenerate_triangles = 0;     // repeated index or zero area (relative tolerance)
  int duplicate_triangles = 0;      // same vertex set (positions) as an earlier triangle
  int edges = 0;                    // undirected edges, after welding coincident vertices
  int boundary_edges = 0;           // used by exactly one triangle
  int unwelded_boundary_edges = 0;  // boundary edges of the triangles as indexed, no welding
                                    // (what tools that do not weld report, e.g. for soups)
  int nonmanifold_edges = 0;        // used by three or more triangles
  int inconsistent_edges = 0;       // two triangles traverse it in the same direction (for
                                    // 3+ uses: the directions do not pair up)
  int components = 0;               // connected components (by shared welded vertices)
  bool closed = false;              // no boundary and no non-manifold edges
  bool consistently_oriented = false;
  bool watertight = false;          // closed and consistently oriented: the "closed" pipeline applies
  double surface_area = 0;
  double signed_volume = 0;         // meaningful when watertight
  Aabb bounds;

  // Multi-line human-readable text; JSON object text.
  std::string ToText() const;
  std::string ToJson() const;
};

// Analyses MESH (any triangle soup). Coincident vertices (exact position) are welded before
// the edge and component analysis; triangles that collapse under welding count as degenerate
// and are left out of it. Throws Error when a vertex is not finite or an index is out of range.
// O(T log T).
MeshReport ValidateMesh(const TriangleMesh& mesh);

}  // namespace contactlab
