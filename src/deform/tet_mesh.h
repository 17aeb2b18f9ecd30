// A coarse tetrahedral simulation mesh embedding a detailed surface (Barbič & James 2008,
// sec. 1.1 and 4.1: the reduced FEM model runs on a coarse mesh; the detailed geometry rides
// along). Built from the interior of a signed distance field by voxelisation.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/aabb.h"
#include "sdf/distance_field.h"

namespace contactlab {

struct TetMesh {
  std::vector<Eigen::Vector3d> vertices;  // #V rest positions, metres
  std::vector<Eigen::Vector4i> tets;      // #T vertex indices, positively oriented
  double cell_size = 0;                   // voxel edge length, metres (0 when not voxelised)

  int num_vertices() const { return int(vertices.size()); }
  int num_tets() const { return int(tets.size()); }
  // Signed volume of tet T (positive for the orientation used here), cubic metres.
  double TetVolume(int t) const;
  double Volume() const;
  Aabb Bounds() const;
  // Volume of the mesh with vertex I displaced by U[3i..3i+2] (U has 3 #V entries).
  double DeformedVolume(const Eigen::VectorXd& u) const;
};

enum class TetSplit { kFive, kSix };

struct VoxelMeshOptions {
  int cells = 16;                  // voxel cells along the longest side of the interior's box
  TetSplit split = TetSplit::kSix; // 6 tets per cell (Kuhn) or 5 (alternating parity)
  bool largest_component = true;   // keep only the largest face-connected set of cells
  // A cell is kept when the field at its centre is below THRESHOLD * (half the cell
  // diagonal), so cells crossed by the surface (and thin parts) are covered.
  double threshold = 1.0;
};

// Voxelises the interior (d < 0) of FIELD. Throws Error naming FIELD's source for an empty
// field, cells outside [1, 256], or a field with no interior.
TetMesh BuildVoxelTetMesh(const DistanceField& field, const VoxelMeshOptions& options = {});

// A box [LO, HI] cut into NX x NY x NZ cells, each split into tets. For tests and benchmarks.
// Throws Error when a count is < 1 or the box is empty.
TetMesh MakeBoxTetMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny,
                       int nz, TetSplit split = TetSplit::kSix);

}  // namespace contactlab
