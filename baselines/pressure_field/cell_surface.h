// The contact surface inside one lattice cell (Elandt et al. 2019 on a sampled field): the cell
// is split into six Kuhn tetrahedra, on each of which the gap and both fields are linear; the
// gap's zero set there is a triangle or a quad, clipped to where the bodies overlap and
// integrated exactly.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "baselines/pressure_field/lattice_blocks.h"
#include "baselines/pressure_field/polygon_clip.h"
#include "baselines/pressure_field/pressure_integration.h"
#include "baselines/pressure_field/pressure_law.h"
#include "baselines/pressure_field/pressure_adjoints.h"

namespace contactlab {

// One lattice cell: its corners by bit (x = 1, y = 2, z = 4) with both fields there, the
// gap at each, and the corners where the bodies overlap.
struct LatticeCell {
  PolyVertex corner[8];
  double g[8];
  std::uint8_t overlapped_at = 0xFF;  // the corners where phi_M + phi_L <= 0, a bit each
};

// What each vertex of a block says about the cells that share it, as bits (BlockVertices).
enum VertexFlag : std::uint8_t {
  kGapPositive = 1,  // g > 0
  kOutsideM = 2,     // phi_M > 0
  kOutsideL = 4,     // phi_L > 0
  kOverlapped = 8,   // phi_M + phi_L <= 0
};

// The gap and the flags at a block's kBlockVerts vertices (lattice_blocks.h), computed once per
// block and shared by the up to eight cells around each vertex.
struct BlockVertices {
  double g[kBlockVerts];
  std::uint8_t flags[kBlockVerts];
};

// Fills V from the fields PHI_M and PHI_L at a block's vertices.
void LoadBlockVertices(const float* phi_M, const float* phi_L, const PressureLaw& law, BlockVertices* v);

// The AND and the OR of the flags of the eight corners of the cell whose first vertex is (CI,
// CJ, CK).
struct CellFlags {
  std::uint8_t all, any;
};
CellFlags CornerFlags(const BlockVertices& v, int ci, int cj, int ck);

// The cell may hold surface: g changes sign over it and no compliant body (CLIP_M, CLIP_L) lies
// wholly outside it.
bool MayHoldSurface(CellFlags f, bool clip_M, bool clip_L);

// The block vertex of the cell (CI, CJ, CK)'s corner C (bit x = 1, y = 2, z = 4).
int CellCornerVertex(int ci, int cj, int ck, int c);

// Loads the corners' fields and gaps of the cell (CI, CJ, CK) of a block with the fields PHI_M and
// PHI_L at its vertices and V from them, and places the corners: the block's first vertex is X0
// (the lattice body's frame), its spacing H.
void LoadCell(const float* phi_M, const float* phi_L, const BlockVertices& v, const Eigen::Vector3d& x0, double h,
              int ci, int cj, int ck, LatticeCell* cell);

// Integrates the surface in CELL over its six tetrahedra into SUMS (and RECORD when not null),
// clipped to where the bodies overlap (ClipToOverlap). Returns the cell's surface area.
// B (null: not wanted): the sums' sensitivities to M's field at the cell's corners are added to
// it (pressure_adjoints.h).
double IntegrateCell(const LatticeCell& cell, const PressureLaw& law, PressureSums* sums, SurfaceRecord* record,
                     CornerSensitivity* b = nullptr);

}  // namespace contactlab
