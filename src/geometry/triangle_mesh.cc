#include "geometry/triangle_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace contactlab {

Aabb TriangleMesh::Bounds() const {
  Aabb box;
  if (triangles.empty()) {
    for (const auto& v : vertices) box.Extend(v);
    return box;
  }
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) box.Extend(vertices[t[k]]);
  }
  return box;
}

double TriangleMesh::MaxVertexRadius() const {
  double r2 = 0;
  for (const Eigen::Vector3d& v : vertices) r2 = std::max(r2, v.squaredNorm());
  return std::sqrt(r2);
}

double TriangleMesh::SurfaceArea() const {
  double area = 0;
  for (const auto& t : triangles) {
    area += 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
  }
  return area;
}

double TriangleMesh::SignedVolume() const {
  double six_volume = 0;
  for (const auto& t : triangles) {
    six_volume += vertices[t[0]].dot(vertices[t[1]].cross(vertices[t[2]]));
  }
  return six_volume / 6.0;
}

Eigen::Vector3d TriangleMesh::FaceNormal(int t) const {
  const auto& f = triangles[t];
  const Eigen::Vector3d n = (vertices[f[1]] - vertices[f[0]]).cross(vertices[f[2]] - vertices[f[0]]);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

void TriangleMesh::Transform(double scale, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  for (auto& v : vertices) v = scale * (R * v) + t;
}

void TriangleMesh::FlipOrientation() {
  for (auto& t : triangles) std::swap(t[1], t[2]);
}

void TriangleMesh::Append(const TriangleMesh& other) {
  const int offset = num_vertices();
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& t : other.triangles) triangles.push_back(t + Eigen::Vector3i::Constant(offset));
}

}  // namespace contactlab
