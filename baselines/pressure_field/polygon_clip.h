// Convex polygons of the pressure-field contact surface and their clipping to each compliant
// body's inside (Sutherland-Hodgman against a field linear on the polygon; Elandt et al. 2019
// keep the surface where both bodies overlap).
#pragma once

#include <Eigen/Core>

namespace contactlab {

// One polygon vertex: position (the lattice body L's frame, metres) and the two fields there.
struct PolyVertex {
  Eigen::Vector3d x;
  double phi_M, phi_L;  // the other body's field and the lattice body's
};

// The point a fraction T of the way from A to B, fields included.
inline PolyVertex Lerp(const PolyVertex& a, const PolyVertex& b, double t) {
  return {a.x + t * (b.x - a.x), a.phi_M + t * (b.phi_M - a.phi_M), a.phi_L + t * (b.phi_L - a.phi_L)};
}

// Vertices a polygon buffer holds: a tetrahedron's quad clipped twice needs 6.
constexpr int kMaxPolygon = 8;

// Clips the convex polygon in BUFFERS[0] (*M vertices) to phi_M <= 0 when CLIP_M, then to
// phi_L <= 0 when CLIP_L; each clip writes into the other buffer. Returns the buffer that holds
// the result, *M its vertex count.
const PolyVertex* ClipToInsides(PolyVertex (&buffers)[2][kMaxPolygon], int* m, bool clip_M, bool clip_L);

}  // namespace contactlab
