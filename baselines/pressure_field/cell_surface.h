// The contact surface inside one lattice cell (Elandt et al. 2019 on a sampled field): the cell
// is split into six Kuhn tetrahedra, on each of which the gap and both fields are linear; the
// gap's zero set there is a triangle or a quad, clipped to where the bodies overlap and
// integrated exactly.
#pragma once

#include <Eigen/Core>

#include "baselines/pressure_field/polygon_clip.h"
#include "baselines/pressure_field/pressure_integration.h"
#include "baselines/pressure_field/pressure_law.h"

namespace contactlab {

// One cell of the lattice: its corners by bit (x = 1, y = 2, z = 4) with both fields there,
// the gap at each, whether every corner lies outside each body, and whether the bodies
// overlap at every corner.
struct LatticeCell {
  PolyVertex corner[8];
  double g[8];
  int positive = 0;  // corners with g > 0
  bool outside_M = true, outside_L = true;
  bool overlapped = true;  // phi_M + phi_L <= 0 at every corner
};

// Loads the cell whose first vertex is (CI, CJ, CK) in a block with the fields PHI_M and PHI_L
// at its vertices (lattice_blocks.h), corners' fields, gaps and flags only. Returns whether the
// cell may hold surface: g changes sign over it and no compliant body (CLIP_M, CLIP_L) lies
// wholly outside it. Only then are its corners placed (PlaceCorners).
bool LoadCell(const float* phi_M, const float* phi_L, int ci, int cj, int ck, const PressureLaw& law, bool clip_M,
              bool clip_L, LatticeCell* cell);

// Places the corners of CELL (CI, CJ, CK) of the block whose first vertex is X0 (the lattice
// body's frame), spacing H.
void PlaceCorners(const Eigen::Vector3d& x0, double h, int ci, int cj, int ck, LatticeCell* cell);

// Integrates the surface in CELL over its six tetrahedra into SUMS (and RECORD when not null),
// clipped to where the bodies overlap (ClipToOverlap). Returns the cell's surface area.
double IntegrateCell(const LatticeCell& cell, const PressureLaw& law, PressureSums* sums, SurfaceRecord* record);

}  // namespace contactlab
