// Generalized winding number of a triangle mesh at a point (Jacobson, Kavan & Sorkine-Hornung
// 2013): the sum of signed solid angles over 4 pi. Used by the soup pipeline of Barbič & James
// 2008, sec. 2.3, to decide which isosurface components enclose others, and by tests as the
// brute-force sign reference.
#pragma once

#include <Eigen/Core>

#include "geometry/triangle_mesh.h"

namespace contactlab {

// Signed solid angle (steradians) of triangle (A, B, C) seen from P (Van Oosterom & Strackee):
// positive when P sees the counter-clockwise side from behind (P on the side opposite the
// normal).
double TriangleSolidAngle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c);

// Winding number of MESH at P: ~1 inside a closed outward-oriented mesh, ~0 outside, -1 inside
// an inward-oriented one; fractional for open meshes. O(#triangles); never throws.
double WindingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p);

}  // namespace contactlab
