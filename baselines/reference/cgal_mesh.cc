// TriangleMesh -> CGAL Surface_mesh conversion for the CGAL references.
#include "baselines/reference/cgal_mesh.h"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <vector>

#include "util/error.h"

namespace contactlab::cgal {

namespace PMP = CGAL::Polygon_mesh_processing;

Mesh ToSurfaceMesh(const TriangleMesh& mesh, const std::string& where, bool require_closed) {
  if (mesh.empty()) Fail(where, "the mesh '" + mesh.name + "' has no triangles");
  std::vector<Point> points;
  points.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(mesh.triangles.size());
  const int n = mesh.num_vertices();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    if (t.minCoeff() < 0 || t.maxCoeff() >= n) Fail(where, "the mesh '" + mesh.name + "' has an invalid vertex index");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) PMP::orient_polygon_soup(points, polygons);
  Mesh out;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, out);
  const bool closed = CGAL::is_closed(out);
  if (require_closed && !closed) Fail(where, "the mesh '" + mesh.name + "' is not closed");
  if (closed) PMP::orient_to_bound_a_volume(out);
  return out;
}

Mesh Transformed(const Mesh& mesh, const Pose& X) {
  Mesh out = mesh;
  const Eigen::Matrix3d R = X.R();
  const Eigen::Vector3d& t = X.translation;
  for (Mesh::Vertex_index v : out.vertices()) {
    const Point& p = out.point(v);
    const Eigen::Vector3d q = R * Eigen::Vector3d(p.x(), p.y(), p.z()) + t;
    out.point(v) = Point(q.x(), q.y(), q.z());
  }
  return out;
}

}  // namespace contactlab::cgal
