// The derivatives of the pressure-field wrench along B's twist (pressure_field_model.h), in
// reverse mode, polygon by polygon. Only M's field at the lattice's vertices depends on B's
// pose: a cut vertex moves along its edge as the gap's zero does, a clip vertex along its edge
// as the overlap's zero does, the pressure follows the local overlap. So the wrench's
// derivative is the sum over the lattice vertices of its sensitivity to M's field there (a
// 6-vector, found here by walking each polygon's integration, clip and cut backwards) times
// that field's derivative along the twist (6 more, pressure_field_model.cc): two 6-vectors
// per vertex instead of six derivatives carried through every polygon.
#pragma once

#include <Eigen/Core>

#include "baselines/pressure_field/polygon_clip.h"
#include "baselines/pressure_field/pressure_law.h"

namespace contactlab {

struct LatticeCell;

// The wrench's (force, then torque about L's origin, L's frame) sensitivity to M's field at
// each of a cell's eight corners (bit x = 1, y = 2, z = 4), a column each.
using CornerSensitivity = Eigen::Matrix<double, 6, 8>;

// A polygon vertex's sensitivities: the wrench's derivative in its position and in its local
// overlap s = phi_M + phi_L.
struct VertexAdjoint {
  Eigen::Matrix<double, 6, 3> x;
  Eigen::Matrix<double, 6, 1> s;
};

// What IntegratePolygon adds for POLY (M vertices, the orientation SIGN it returned), its
// derivative in each vertex's position and overlap, into OUT.
void PolygonAdjoints(const PolyVertex* poly, int m, double sign, const PressureLaw& law,
                     VertexAdjoint* out);
// PolygonAdjoints and then CutAdjoints for a polygon that is a tetrahedron's cut itself (no
// clip: the tetrahedron overlaps throughout), in one pass: each vertex moves only along its edge of
// the cell, so only its position sensitivity along that edge is formed, never the 6x3 whole.
// POLY (M vertices) came from CELL's corners as ORIGIN says; SIGN is IntegratePolygon's.
void CutPolygonAdjoints(const LatticeCell& cell, const PolyVertex* poly, int m, double sign, const PressureLaw& law,
                        const VertexOrigin* origin, CornerSensitivity* b);
// Through a clip: the M clipped vertices' adjoints OUT_ADJ (ORIGIN: vertices of IN, N of them),
// added to IN_ADJ.
void ClipAdjoints(const PolyVertex* in, const VertexOrigin* origin, const VertexAdjoint* out_adj, int m,
                  VertexAdjoint* in_adj);
// Through a tetrahedron's cut: the N cut vertices' adjoints ADJ (ORIGIN: corners of CELL), added
// to the corners' sensitivities *B.
void CutAdjoints(const LatticeCell& cell, const PressureLaw& law, const VertexOrigin* origin, const VertexAdjoint* adj,
                 int n, CornerSensitivity* b);

}  // namespace contactlab
