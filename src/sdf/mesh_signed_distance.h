// Exact signed distance to a closed triangle mesh, per point in O(log #triangles): the
// closest triangle by a BVH (TriangleBvh), the sign by the angle-weighted pseudo-normal of the
// closest feature (Bærentzen & Aanæs 2005, "Signed distance computation using the angle
// weighted pseudonormal"). The reference of the deformed distance field (Barbič & James 2008,
// sec. 4.2, Fig. 10): the deformed surface mesh changes with q, so a BVH rebuilt per pose and
// a logarithmic sign are what make exact distances affordable at tens of thousands of points;
// the winding number (sdf/winding_number.h) is O(#triangles) per point.
//
// The sign is exact (up to rounding near feature boundaries) for a closed, consistently
// oriented 2-manifold without self-intersections: every edge has exactly two faces, which use
// it in opposite directions. The deformed surface of a reduced model keeps the rest mesh's
// topology, so this holds for any moderate deformation of a closed rest mesh.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "sdf/triangle_bvh.h"

namespace contactlab {

class MeshSignedDistance {
 public:
  // MESH: closed, outward (counter-clockwise) oriented 2-manifold, metres. Throws Error naming
  // WHERE and the mesh when an edge does not have exactly two faces using it in opposite
  // directions, or the mesh is empty.
  MeshSignedDistance(const TriangleMesh& mesh, const std::string& where);

  // Signed distance at P (negative inside). CLOSEST (may be null) gets the closest point.
  // Never throws or allocates.
  double Distance(const Eigen::Vector3d& p, Eigen::Vector3d* closest = nullptr) const;

  // True when P is inside, given the triangle T closest to P (its index in the mesh): the
  // pseudo-normal test alone, for callers that found the closest triangle themselves.
  // CLOSEST (may be null) gets the closest point. Never throws or allocates.
  bool Inside(const Eigen::Vector3d& p, std::int32_t t, Eigen::Vector3d* closest = nullptr) const;

  const TriangleMesh& mesh() const { return mesh_; }

 private:
  TriangleMesh mesh_;
  TriangleBvh bvh_;
  std::vector<Eigen::Vector3d> face_normal_;    // #T unit normals (zero when degenerate)
  std::vector<Eigen::Vector3d> edge_normal_;    // #T x 3: edge (v_e, v_{e+1}), sum of its two face normals
  std::vector<Eigen::Vector3d> vertex_normal_;  // #V angle-weighted sums of face normals
};

}  // namespace contactlab
