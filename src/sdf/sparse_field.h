// A narrow-band signed distance field: fine samples only in the contact layer, a coarse field
// in free space (the hybrid Barbič & James 2008 propose as future work in sec. 8, after
// Voxmap-PointShell's coarse voxmap and fine surface layer). It sits behind DistanceField, so
// every model, the tree's culling and the vectorised lookups use it unchanged.
//
// Layout, for a fine grid of spacing h whose dims are 8 B + 1 per axis (B bricks):
//  * a coarse grid of spacing H = 8 h with the same origin and box, (B + 1) points per axis,
//    holding the closed pipeline's signed distances (build_distance_field.h);
//  * one slot per brick (a coarse cell = 8^3 fine cells): the index of its stored samples, or
//    kOutside / kInside when it holds none;
//  * a stored brick keeps its 9^3 fine samples (a one-sample overlap with its neighbours, so a
//    trilinear lookup never leaves its brick) as 16-bit integers times one quantum for the whole
//    field. Two x-neighbours are one 32-bit load, so a lookup is one slot and four sample loads.
//
// What the values are:
//  * a brick is stored when one of its samples has |d| <= band = BAND_VOXELS h. Its samples with
//    |d| < band + h are exact (as the dense field's band, rounded to the quantum); farther ones
//    are |d| >= band + h and hold the coarse value there, clamped to that bound;
//  * in a brick not stored every sample has |d| > band, so |d| >= floor = band - sqrt(3)/2 h in
//    all of it, with one sign. Outside the body the lookup is the largest of three lower
//    bounds: floor; D_H - sqrt(3)/2 H, D_H the coarse trilinear interpolant (the trilinear
//    weights put the corners within sqrt(3)/2 H of the point on average, and the distance is
//    1-Lipschitz); and D_k - |p - c_k| for each corner c_k (tight near the corners). Inside it
//    is min(-floor, D_H): depth beyond the band at the coarse resolution. Stored samples
//    beyond band + h get the same bounds at build time.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "sdf/field_grid.h"
#include "sdf/mesh_signed_distance.h"

namespace contactlab {

struct SparseFieldStorage {
  static constexpr int kBrick = 8;          // fine cells per brick edge (= H / h)
  static constexpr int kBrickEdge = 9;      // samples per brick edge
  static constexpr int kBrickStride = 730;  // 16-bit words per stored brick: 9^3 samples and a pad
  static constexpr std::int32_t kOutside = -1, kInside = -2;
  static constexpr int kMinResolution = 64;  // cells along the longest side: 8 bricks at least
  static constexpr int kMaxBand = 16;        // voxels
  // Whether a field of RESOLUTION cells can be sparse: whole bricks, kMinResolution at least.
  static constexpr bool ResolutionFits(int resolution) {
    return resolution % kBrick == 0 && resolution >= kMinResolution;
  }

  Eigen::Vector3i bricks = Eigen::Vector3i::Zero();  // per axis
  std::vector<float> coarse;                          // (bricks + 1) per axis, x fastest, metres
  std::vector<std::int32_t> slot;                     // per brick, x fastest
  std::vector<std::int16_t> samples;                  // kBrickStride per stored brick, x fastest
  float quantum = 0;  // metres per sample unit
  int band_voxels = 0;
  // Derived from the fine spacing h and the band by SetSpacing (not stored in files): the |d|
  // lower bound in a brick not stored, band - sqrt(3)/2 h; sqrt(3)/2 H; and H = 8 h, metres.
  float floor = 0, margin = 0, coarse_spacing = 0;

  void SetSpacing(double h);

  std::int64_t num_stored() const { return std::int64_t(samples.size()) / kBrickStride; }
  std::int64_t memory_bytes() const {
    return std::int64_t(coarse.size() * sizeof(float) + slot.size() * sizeof(std::int32_t) +
                        samples.size() * sizeof(std::int16_t));
  }
  std::int64_t BrickIndex(int bx, int by, int bz) const {
    return bx + std::int64_t(bricks.x()) * (by + std::int64_t(bricks.y()) * bz);
  }
  std::int64_t CoarseIndex(int i, int j, int k) const {
    return i + std::int64_t(bricks.x() + 1) * (j + std::int64_t(bricks.y() + 1) * k);
  }

  // Fine sample (i, j, k), 0 <= i <= 8 bricks.x() etc.
  float Sample(int i, int j, int k) const;
  // Distance at fine-grid coordinates G inside the box (in [0, 8 bricks] per axis), and its
  // gradient per fine-grid unit (divide by h) when GRADIENT is not null.
  double Lookup(const Eigen::Vector3d& g, Eigen::Vector3d* gradient = nullptr) const;
  // Throws Error (WHERE) when the arrays disagree with BRICKS or each other, a slot is out of
  // range, a number is not finite, or the band is below one voxel.
  void Validate(const std::string& where) const;
};

// The storage of MESH's field on the fine grid that refines COARSE_GRID 8 times, given the
// closed pipeline's samples COARSE on COARSE_GRID (signed_distance_grid.h) and SIGN built from
// the same closed MESH. Exact distances come from every triangle whose box, grown by
// BAND_VOXELS + 1 fine voxels, reaches a brick (in parallel over bricks); their signs from
// SIGN's pseudo-normals. Throws nothing beyond allocation failure.
SparseFieldStorage BuildSparseStorage(const TriangleMesh& mesh, const MeshSignedDistance& sign,
                                      const FieldGrid& coarse_grid, std::vector<float> coarse, int band_voxels);

}  // namespace contactlab
