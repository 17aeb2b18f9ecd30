// The deformable pointshell and its point-based BD-tree (Barbič & James 2008, sec. 4.1).
// Every point of a pointshell is embedded in the reduced model's simulation mesh, so at
// reduced coordinates q it sits at x = X + U q with normal normalize(n + N q)
// (EmbeddedPoints, smooth gradient modes). The tree's spheres are centred on the deformed
// points themselves; a node's radius at q is the conservative bound
//     R(q) = R_0 + sum_j |q_j| rho_j,
// R_0 the rest radius (Pointshell::node_radius) and rho_j the largest distance, over the
// node's subtree, between mode j's displacement at a point and at the node's own point:
// |x_Q - x_C| = |X_Q - X_C + sum_j q_j (U_Qj - U_Cj)| <= R_0 + sum_j |q_j| rho_j.
// Radii are evaluated only for the nodes a traversal visits, with |q| computed once a cycle.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "deform/embedded_points.h"
#include "pointshell/pointshell.h"

namespace contactlab {

class DeformablePointshell {
 public:
  // Embeds SHELL (body frame, metres) in MESH with basis U (3#V x r). Throws Error as
  // EmbeddedPoints does.
  DeformablePointshell(std::shared_ptr<const Pointshell> shell, const TetMesh& mesh, const Eigen::MatrixXd& U);

  const Pointshell& shell() const { return *shell_; }
  const EmbeddedPoints& points() const { return points_; }
  int r() const { return points_.r(); }

  // rho_j of NODE, r entries (metres per unit q_j), then zeros up to the basis stride.
  const float* node_spread(int node) const { return &rho_[std::size_t(node) * points_.basis_stride()]; }
  // Largest displacement per unit q_j of any point relative to any node's own point, plus of
  // any point itself: c_j = max_n rho_nj + max_i |U_ij|. A change dq moves every point and
  // grows every radius by at most sum_j c_j |dq_j| together.
  float mode_travel(int j) const { return travel_[j]; }
  // The same bound for one node (temporal coherence under deformation): c_nj = rho_nj + |U_cj|,
  // c the node's own point, so between q0 and q the node's ball moves and grows by at most
  // sum_j c_nj |q_j - q0_j| (its point by |U_c (q - q0)|, its radius by the rho terms). Laid
  // out as node_spread; rounded up to float.
  const float* node_travel(int node) const { return &node_travel_[std::size_t(node) * points_.basis_stride()]; }
  // sum_j c_nj |q_j - q0_j| in single precision for the hot loop; Q and Q0 zero past r up to the
  // basis stride. Rounded up by a relative 1e-5 so float summation cannot undercut it.
  float NodeTravelF(int node, const float* q, const float* q0) const {
    return StrideSum(node_travel(node), [&](int j) { return std::fabs(q[j] - q0[j]); }) * (1.f + 1e-5f);
  }
  // R(q) in single precision for the hot loop, ABS_Q as float, zero past r up to the basis
  // stride.
  float RadiusF(int node, const float* abs_q) const {
    return shell_->node_radius[node] + StrideSum(node_spread(node), [&](int j) { return abs_q[j]; });
  }
  // R(q) of NODE; ABS_Q holds |q_j| (r entries). No allocation.
  double Radius(int node, const double* abs_q) const {
    const float* rho = node_spread(node);
    double R = shell_->node_radius[node];
    for (int j = 0; j < r(); ++j) R += double(rho[j]) * abs_q[j];
    return R;
  }

 private:
  // sum_j ROW[j] TERM(j) over the basis stride in eight partial sums: independent multiply-adds
  // the compiler packs into vectors, not one chain of r dependent ones.
  template <class Term>
  float StrideSum(const float* row, Term&& term) const {
    static_assert(EmbeddedPoints::kBasisLanes == 8);
    float s[EmbeddedPoints::kBasisLanes] = {};
    for (int j = 0; j < points_.basis_stride(); j += EmbeddedPoints::kBasisLanes) {
      for (int l = 0; l < EmbeddedPoints::kBasisLanes; ++l) s[l] += row[j + l] * term(j + l);
    }
    return ((s[0] + s[4]) + (s[1] + s[5])) + ((s[2] + s[6]) + (s[3] + s[7]));
  }

  std::shared_ptr<const Pointshell> shell_;
  EmbeddedPoints points_;
  std::vector<float> rho_;     // (#N x stride) rho_[n stride + j], rounded up to float
  std::vector<float> travel_;  // (r) mode_travel
  std::vector<float> node_travel_;  // (#N x stride) node_travel
};

}  // namespace contactlab
