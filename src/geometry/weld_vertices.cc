// Exact-position vertex welding by sorting (no hashing of floating-point keys).
#include "geometry/weld_vertices.h"

#include <algorithm>
#include <numeric>

namespace contactlab {

std::vector<int> FindExactDuplicateVertices(const std::vector<Eigen::Vector3d>& p) {
  const int n = static_cast<int>(p.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  // Lexicographic by (x, y, z), then by index so the first of each run is the smallest.
  std::sort(order.begin(), order.end(), [&p](int a, int b) {
    const Eigen::Vector3d& pa = p[a];
    const Eigen::Vector3d& pb = p[b];
    if (pa.x() != pb.x()) return pa.x() < pb.x();
    if (pa.y() != pb.y()) return pa.y() < pb.y();
    if (pa.z() != pb.z()) return pa.z() < pb.z();
    return a < b;
  });
  std::vector<int> rep(n);
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && p[order[j]] == p[order[i]]) ++j;
    for (int k = i; k < j; ++k) rep[order[k]] = order[i];
    i = j;
  }
  return rep;
}

TriangleMesh WeldExactDuplicateVertices(const TriangleMesh& mesh) {
  const std::vector<int> rep = FindExactDuplicateVertices(mesh.vertices);
  TriangleMesh welded;
  welded.name = mesh.name;
  std::vector<int> new_index(mesh.vertices.size(), -1);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    if (rep[i] == i) {
      new_index[i] = welded.num_vertices();
      welded.vertices.push_back(mesh.vertices[i]);
    }
  }
  welded.triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    welded.triangles.emplace_back(new_index[rep[t[0]]], new_index[rep[t[1]]], new_index[rep[t[2]]]);
  }
  return welded;
}

}  // namespace contactlab
