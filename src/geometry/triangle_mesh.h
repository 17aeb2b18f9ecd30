// A triangle mesh that may be a polygon soup: no manifoldness, closedness or consistent
// orientation is assumed. Validation (geometry/mesh_validation.h) says which of those hold.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/aabb.h"

namespace contactlab {

// Largest coordinate magnitude ContactLab accepts anywhere (metres): a mesh after loading and
// scaling, a field's grid. Squared distances, volumes and winding numbers stay finite well
// inside this bound; 1e30 or "--scale 1e300" are refused, naming the limit.
inline constexpr double kMaxCoordinate = 1e9;

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;   // #V positions, metres once loaded with a scale
  std::vector<Eigen::Vector3i> triangles;  // #T vertex indices, counter-clockwise = outward
  std::string name;                        // file name or procedural description

  int num_vertices() const { return static_cast<int>(vertices.size()); }
  int num_triangles() const { return static_cast<int>(triangles.size()); }
  bool empty() const { return triangles.empty(); }

  // Bounding box of the vertices referenced by triangles (all vertices if none).
  Aabb Bounds() const;
  // Largest distance of a vertex from the origin of the mesh's frame (a body's origin once
  // loaded), metres; 0 without vertices. Every point of the mesh lies within it, however the
  // body turns about its origin: the bound a motion of the body puts on its points' speed.
  double MaxVertexRadius() const;
  // Sum of triangle areas.
  double SurfaceArea() const;
  // Signed volume by the divergence theorem; meaningful only for closed, oriented meshes.
  double SignedVolume() const;
  // Unit normal of triangle T (zero for a degenerate triangle).
  Eigen::Vector3d FaceNormal(int t) const;
  // Applies p <- scale * R * p + t to every vertex (R a rotation).
  void Transform(double scale, const Eigen::Matrix3d& R, const Eigen::Vector3d& t);
  // Reverses every triangle's orientation.
  void FlipOrientation();
  // Appends OTHER's vertices and triangles.
  void Append(const TriangleMesh& other);
};

}  // namespace contactlab
