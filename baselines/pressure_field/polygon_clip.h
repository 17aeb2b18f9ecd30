// Convex polygons of the pressure-field contact surface and their clipping to where the bodies
// overlap (Sutherland-Hodgman against a field linear on the polygon; Elandt et al. 2019 keep
// the surface where both bodies overlap).
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

// Vertices a polygon buffer holds: a tetrahedron's quad clipped once needs 5.
constexpr int kMaxPolygon = 8;

// Where a vertex made by a cut or a clip comes from: the fraction T of the way from vertex A to
// vertex B of what was cut (B < 0: vertex A itself), so its derivatives can follow.
struct VertexOrigin {
  int a, b;
  double t;
};

// Clips the convex polygon in BUFFERS[0] (*M vertices), a piece of the contact surface, to the
// bodies' overlap phi_M + phi_L <= 0, into BUFFERS[1]. Returns BUFFERS[1], *M its vertex count.
// On the surface the two bodies' depths have one sign (each is its compliance times the
// pressure; a rigid body's is 0), so this is the clip to both insides; clipping by their sum,
// the local overlap, keeps it well conditioned when one body is much stiffer than the other,
// whose depth is then rounding-sized and of either sign. ORIGIN (null: not wanted) receives
// where each output vertex comes from among the input's.
const PolyVertex* ClipToOverlap(PolyVertex (&buffers)[2][kMaxPolygon], int* m, VertexOrigin* origin = nullptr);

}  // namespace contactlab
