// The lattice the pressure-field surface is extracted on, in blocks of 4x4x4 cells, and the
// culling that keeps only the blocks that may hold surface (pressure_field_model.h; the
// extraction of Elandt et al. 2019 on sampled fields instead of tetrahedral meshes).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "baselines/pressure_field/pressure_law.h"
#include "geometry/aabb.h"
#include "geometry/pose.h"
#include "sdf/distance_field.h"

namespace contactlab {

constexpr int kBlock = 4;                  // cells per block side
constexpr int kVerts = kBlock + 1;         // vertices per block side
constexpr int kBlockVerts = kVerts * kVerts * kVerts;
constexpr double kCullMargin = 0.5;        // cells: blocks kept within this of the surface (rounding)

// A block's vertex (I, J, K) in its kBlockVerts samples, x fastest.
inline int VertexIndex(int i, int j, int k) { return i + kVerts * (j + kVerts * k); }

// A set of a block's vertices, one bit each.
struct VertexMask {
  static_assert(kBlockVerts <= 128);
  std::uint64_t bits[2] = {0, 0};

  bool Has(int v) const { return (bits[v >> 6] >> (v & 63)) & 1; }
  void Add(int v) { bits[v >> 6] |= std::uint64_t(1) << (v & 63); }
};

// The lattice of spacing H (metres) on the lattice body L's grid (origin O_L, L's frame) that
// covers the overlap of L's box BOX_L and the other body's box BOX_M placed at X_LM: its
// *ORIGIN and *CELLS per axis. False (and nothing written) when the boxes do not overlap.
bool FitLattice(const Aabb& box_M, const Aabb& box_L, const Eigen::Vector3d& o_L, const Pose& X_LM, double h,
                Eigen::Vector3d* origin, Eigen::Vector3i* cells);

// The lattice's blocks that may hold surface, by an octree from a cube of ROOT cells: a node
// is dropped when its centre proves, by the fields' Lipschitz bound LIPSCHITZ (the gap's too:
// it weighs the fields by weights that sum to 1), that it lies outside a body or holds no zero
// of LAW's gap. FIELD_L is in the lattice's frame, FIELD_M at X_ML. Writes up to CAPACITY
// blocks' first cells to BLOCKS (the rest are not rendered) and returns their number; adds the
// nodes examined to *NODES. LIMIT (> 0): once more than LIMIT blocks qualify the culling stops
// and returns LIMIT + 1 (a time budget's test: the lattice is too fine).
std::int64_t CullBlocks(const DistanceField& field_L, const DistanceField& field_M, const Pose& X_ML,
                        const PressureLaw& law, const Eigen::Vector3d& origin, const Eigen::Vector3i& cells,
                        double h, int root, double lipschitz, std::array<std::int32_t, 3>* blocks,
                        std::int64_t capacity, std::int64_t* nodes, std::int64_t limit = 0);

// FIELD (the lattice body's) at the kBlockVerts vertices of the block whose first cell is BLK,
// on the lattice (ORIGIN, spacing H: on FIELD's grid, every H / spacing-th point, as FitLattice
// places it), into PHI: a dense field's samples where the block lies inside its grid, else its
// Distance.
void SampleBlock(const DistanceField& field, const Eigen::Vector3d& origin, double h,
                 const std::array<std::int32_t, 3>& blk, float* phi);

// The lattice seen from the other body M: X_ML, and one lattice step along each of L's axes in
// M's frame, so a block's vertices are reached by additions.
struct LatticeInOther {
  LatticeInOther(const Pose& X_ML, double h);

  Pose X_ML;
  Eigen::Vector3d step_i, step_j, step_k;
};

// M's FIELD at the kBlockVerts vertices of the block whose first vertex is X0 (L's frame),
// into PHI.
void SampleBlockInOther(const DistanceField& field, const LatticeInOther& lattice, const Eigen::Vector3d& x0,
                        float* phi);

}  // namespace contactlab
