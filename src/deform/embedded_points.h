// Material points embedded in a reduced deformable model (Barbič & James 2008, sec. 4.1):
// u = U q per point, with U (3 x r) interpolated from the basis by the enclosing tet's shape
// functions, and deformed normals by deformation-gradient push-forward n' ~ F^{-T} n, with
// F = I + sum_j F_j q_j. Precomputed once per point in flat arrays; evaluated per haptic
// cycle without allocation.
//
// Gradient modes F_j. The gradient of the piecewise-linear displacement is constant per tet
// and jumps across tet faces, so normals computed from it jump as a point's tet changes
// (kPerTet). kSmooth instead averages the tets' gradient modes at each vertex (weighted by tet
// volume) and interpolates those vertex gradients with the point's barycentric coordinates:
// F_j is then continuous across faces, and still exact wherever the displacement is affine
// (every tet has the same gradient there).
//
// Normal correction (paper sec. 4.1). To first order in q, F^{-T} n = n - sum_j (F_j^T n) q_j,
// so each point stores the 3 x r normal-correction matrix N_i = -[F_1^T n ... F_r^T n] and
// CorrectedNormal(i, q) = normalize(n + N_i q): 3r multiply-adds like the position, linear in
// q, and continuous across faces with kSmooth.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "deform/tet_mesh.h"
#include "reduced/reduced_state.h"
#include "util/aligned_vector.h"

namespace contactlab {

enum class GradientScheme { kPerTet, kSmooth };

class EmbeddedPoints {
 public:
  EmbeddedPoints() = default;
  // Embeds POINTS (rest frame, metres) with rest NORMALS (unit, or empty for none) into MESH
  // with basis U (3#V x r). A point outside every tet uses the tet it is least outside of
  // (barycentric extrapolation). Throws Error when sizes disagree or the mesh is empty.
  // SCHEME: how the gradient modes F_j (and so the normals) are formed (see above).
  EmbeddedPoints(const TetMesh& mesh, const Eigen::MatrixXd& U, const std::vector<Eigen::Vector3d>& points,
                 const std::vector<Eigen::Vector3d>& normals = {}, GradientScheme scheme = GradientScheme::kSmooth);

  int size() const { return int(tet_.size()); }
  int r() const { return r_; }
  // The rows of every U_i for vector kernels (deform/reduced_point_batch.h): row c of point i
  // at basis_rows() + (3 i + c) basis_stride(), its r entries then zeros up to the stride, r
  // rounded up to kBasisLanes floats. Starts on a cache line; at r = 15 a point's three rows
  // are exactly three lines.
  static constexpr int kBasisLanes = 8;
  int basis_stride() const { return stride_; }
  const float* basis_rows() const { return u_.data(); }
  // The rows of every normal-correction matrix N_i, laid out as basis_rows().
  const float* normal_rows() const { return nc_.data(); }
  int tet(int i) const { return tet_[i]; }
  // Barycentric coordinates of point I (4 entries, sum 1; all >= 0 inside its tet).
  Eigen::Vector4d barycentric(int i) const { return Eigen::Map<const Eigen::Vector4d>(&bary_[4 * i]); }
  Eigen::Vector3d rest_position(int i) const { return Eigen::Map<const Eigen::Vector3f>(&rest_[3 * i]).cast<double>(); }

  // The point's 3 x r basis U_i (allocates; for setup and tests).
  Eigen::MatrixXd Basis(int i) const;

  // Hot path (no allocation): displacement U_i q, deformed position, deformation gradient and
  // deformed unit normal of point I for reduced coordinates Q (r entries).
  Eigen::Vector3d Displacement(int i, const double* q) const;
  Eigen::Vector3d Position(int i, const double* q) const { return rest_position(i) + Displacement(i, q); }
  Eigen::Matrix3d DeformationGradient(int i, const double* q) const;
  Eigen::Vector3d Normal(int i, const double* q) const;  // exact push-forward F^{-T} n, unit
  // normalize(n + N_i q): the linear normal correction, renormalised (unit; n at q = 0).
  Eigen::Vector3d CorrectedNormal(int i, const double* q) const;
  GradientScheme scheme() const { return scheme_; }
  // F_q += U_i^T FORCE: the reduced force of a point force (newtons) applied at point I.
  void AddPointForce(int i, const Eigen::Vector3d& force, double* f_q) const;

  // W = U_i^T V (r entries, float) for a vector V at point I: a deformed field's proxy force.
  // Positions and normals of many points: deform/reduced_point_batch.h.
  void ProjectF(int i, const float* v, float* w) const {
    const float* row = &u_[3 * std::size_t(i) * stride_];
    for (int j = 0; j < r_; ++j) w[j] = row[j] * v[0] + row[stride_ + j] * v[1] + row[2 * stride_ + j] * v[2];
  }

 private:
  int r_ = 0;
  int stride_ = 0;  // basis_stride()
  GradientScheme scheme_ = GradientScheme::kSmooth;
  std::vector<int> tet_;       // #P enclosing tet
  std::vector<double> bary_;   // #P x 4 barycentric coordinates
  std::vector<float> rest_;    // #P x 3 rest positions
  std::vector<float> normal_;  // #P x 3 rest normals (zero when none were given)
  AlignedVector<float> u_;     // #P x 3 x stride: row c of U_i at u_[(3 i + c) stride]
  std::vector<float> f_;       // #P x 9 x r: entry (a, b) of F_j at f_[(9 i + 3 a + b) r + j]
  AlignedVector<float> nc_;    // #P x 3 x stride: row c of N_i at nc_[(3 i + c) stride]
};

// Index of the tet containing P, or the one P is least outside of, and its barycentric
// coordinates. O(#T) per call; EmbeddedPoints uses a grid instead.
int LocateInTetMesh(const TetMesh& mesh, const Eigen::Vector3d& p, Eigen::Vector4d* bary);

}  // namespace contactlab
