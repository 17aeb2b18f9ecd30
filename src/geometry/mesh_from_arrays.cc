// MeshFromArrays: a TriangleMesh from row-major arrays, with the file readers' checks and
// messages (obj_reader.cc, off_reader.cc, ply_reader.cc, LoadMesh's coordinate limit).
#include "geometry/mesh_from_arrays.h"

#include <charconv>
#include <climits>
#include <cstdio>

#include "util/error.h"

namespace contactlab {
namespace {

// "(x, y, z)", each the shortest text that reads back as the value ("nan", "inf" as they are).
std::string VertexText(const Eigen::Vector3d& p) {
  std::string s = "(";
  for (int a = 0; a < 3; ++a) {
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, p[a]);
    s.append(a > 0 ? ", " : "").append(buf, ec == std::errc() ? end : buf);
  }
  return s + ")";
}

// The readers' message for a face's vertex INDEX outside [0, NV), naming TRIANGLE.
[[noreturn]] void FailIndex(std::size_t triangle, std::int64_t index, std::size_t nv, std::string_view where) {
  Fail(where, "triangle " + std::to_string(triangle) + ": face vertex index " + std::to_string(index) +
                  " out of range [0, " + std::to_string(nv) + ")");
}

}  // namespace

TriangleMesh MeshFromArrays(std::span<const double> vertices, std::span<const std::int64_t> triangles,
                            std::string name, std::string_view where) {
  // Shapes: whole rows of three, counts that fit the mesh's int indices.
  if (vertices.size() % 3 != 0) {
    Fail(where, "vertices hold " + std::to_string(vertices.size()) + " numbers, not rows of 3 (x, y, z)");
  }
  if (triangles.size() % 3 != 0) {
    Fail(where, "triangles hold " + std::to_string(triangles.size()) + " indices, not rows of 3");
  }
  const std::size_t nv = vertices.size() / 3;
  const std::size_t nt = triangles.size() / 3;
  if (nv >= std::size_t(INT_MAX)) Fail(where, "too many vertices");
  if (nt >= std::size_t(INT_MAX)) Fail(where, "too many triangles");

  // Indices checked at full width before they narrow to the mesh's int.
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (triangles[i] < 0 || triangles[i] >= std::int64_t(nv)) FailIndex(i / 3, triangles[i], nv, where);
  }
  TriangleMesh mesh;
  mesh.name = std::move(name);
  mesh.vertices.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) mesh.vertices.emplace_back(vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]);
  mesh.triangles.reserve(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    mesh.triangles.emplace_back(int(triangles[3 * t]), int(triangles[3 * t + 1]), int(triangles[3 * t + 2]));
  }
  CheckMeshContent(mesh, where);
  return mesh;
}

void CheckMeshContent(const TriangleMesh& mesh, std::string_view where) {
  // Vertices: finite, and within the coordinate limit every loaded mesh keeps to.
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices[i];
    if (!p.allFinite()) Fail(where, "vertex " + std::to_string(i) + " is not finite: " + VertexText(p));
    if (!(p.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "coordinates out of range: |coordinate| reaches %.3g m (the limit is %.0e m)",
                    p.cwiseAbs().maxCoeff(), kMaxCoordinate);
      Fail(where, "vertex " + std::to_string(i) + ": " + buf);
    }
  }
  // Triangles: at least one, every index naming a vertex.
  if (mesh.triangles.empty()) Fail(where, "no faces: the mesh has no triangles");
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int index = mesh.triangles[t][k];
      if (index < 0 || index >= mesh.num_vertices()) FailIndex(std::size_t(t), index, mesh.vertices.size(), where);
    }
  }
}

}  // namespace contactlab
