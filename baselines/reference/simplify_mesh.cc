// Edge-collapse simplification of a mesh for display.
#include "baselines/reference/simplify_mesh.h"

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "baselines/reference/cgal_mesh.h"
#include "util/error.h"

namespace contactlab {

TriangleMesh SimplifyMesh(const TriangleMesh& mesh, int max_triangles, const std::string& where) {
  if (max_triangles < 4) Fail(where, "a triangle budget of " + std::to_string(max_triangles) + " is below 4");
  if (mesh.num_triangles() <= max_triangles) return mesh;
  cgal::Mesh m = cgal::ToSurfaceMesh(mesh, where, false);
  // A triangle mesh has 3/2 edges per triangle (plus half its border edges).
  CGAL::Surface_mesh_simplification::Count_stop_predicate<cgal::Mesh> stop(std::size_t(max_triangles) * 3 / 2);
  CGAL::Surface_mesh_simplification::edge_collapse(m, stop);
  m.collect_garbage();
  TriangleMesh out;
  out.name = mesh.name;
  out.vertices.reserve(m.number_of_vertices());
  for (cgal::Mesh::Vertex_index v : m.vertices()) {
    const cgal::Point& p = m.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  out.triangles.reserve(m.number_of_faces());
  for (cgal::Mesh::Face_index f : m.faces()) {
    Eigen::Vector3i t;
    int k = 0;
    for (cgal::Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if (k < 3) t[k] = int(v.idx());
      ++k;
    }
    if (k == 3) out.triangles.push_back(t);
  }
  return out;
}

}  // namespace contactlab
