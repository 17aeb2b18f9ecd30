// Reduced St. Venant-Kirchhoff internal forces and tangent stiffness as exact cubic and
// quadratic polynomials in the reduced coordinates q (Barbič & James 2005, sec. 3; used by
// Barbič & James 2008, sec. 4.1), and the linear modal variant (constant stiffness).
//
// With u = U q and linear tets, the StVK energy is a quartic polynomial W(q); its gradient
//   f(q) = A q + B(q, q) + C(q, q, q)
// has fully symmetric coefficient tensors A (r x r), B (r x r x r), C (r x r x r x r),
// precomputed exactly by summing per-element contributions. Evaluation writes
//   Kb = B(q, .), Kc = C(q, q, .)   =>   f = (A + Kb + Kc) q,   K = A + 2 Kb + 3 Kc.
// Kc, the r^4 part, is one product of the symmetric npairs x npairs matrix of C with the
// monomials q_l q_m; it reads only the upper half of that matrix (packed, SIMD: see
// symmetric_packed_product.h), the largest array the time step streams.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "reduced/reduced_state.h"
#include "deform/stvk_fem.h"

namespace contactlab {

class Progress;

enum class ReducedModelKind : std::int32_t { kStVK = 0, kLinear = 1 };

class ReducedInternalForces {
 public:
  // Scratch for Evaluate, sized once by MakeWorkspace.
  struct Workspace {
    Eigen::VectorXd w;   // npairs monomials q_l q_m (l <= m), times 2 when l < m
    Eigen::VectorXd kb;  // npairs entries of Kb (upper triangle, pair order)
    Eigen::VectorXd kc;  // npairs entries of Kc
    ReducedMatrix T;     // r x r: A + Kb + Kc (the secant matrix, f = T q)
  };

  ReducedInternalForces() = default;
  // From stored coefficients (model files). A is r x r; for kStVK, B is npairs x r and C is
  // npairs x npairs (see Compute), npairs = r (r + 1) / 2; for kLinear B and C are empty.
  // Throws Error naming WHERE when sizes disagree, r exceeds kMaxReducedModes, or C is not
  // symmetric (C(p, k) / w_k = C(k, p) / w_p with the pair weights w, to 1e-9 relative).
  ReducedInternalForces(ReducedModelKind kind, Eigen::MatrixXd A, Eigen::MatrixXd B, Eigen::MatrixXd C,
                        const std::string& where = "reduced forces");

  // Exact coefficients for basis U (3#V x r) of FEM. Throws Error when r is out of
  // [1, kMaxReducedModes] or U has the wrong row count.
  static ReducedInternalForces Compute(const StVKFem& fem, const Eigen::MatrixXd& U, ReducedModelKind kind,
                                       Progress* progress = nullptr);

  int r() const { return r_; }
  int num_pairs() const { return r_ * (r_ + 1) / 2; }
  ReducedModelKind kind() const { return kind_; }
  const Eigen::MatrixXd& linear() const { return A_; }     // A = U^T K U, r x r
  const Eigen::MatrixXd& quadratic() const { return B_; }  // B(pair(i,j), l) = B_ijl
  // C(pair(i,j), pair(l,m)) = C_ijlm * (l == m ? 1 : 2)
  const Eigen::MatrixXd& cubic() const { return C_; }
  int Pair(int i, int j) const { return pair_[i * r_ + j]; }

  Workspace MakeWorkspace() const;
  // Reduced internal force f(q) (r) and, when K is not null, the tangent stiffness df/dq
  // (r x r). Q has r entries; WS comes from this object's MakeWorkspace. Allocates nothing,
  // throws nothing.
  void Evaluate(const ReducedVector& q, ReducedVector* f, ReducedMatrix* K, Workspace* ws) const;
  // Elastic energy W(q), joules.
  double Energy(const ReducedVector& q, Workspace* ws) const;

 private:
  void BuildPairTable();
  // cubic_packed_ from C_.
  void PackCubic();

  ReducedModelKind kind_ = ReducedModelKind::kStVK;
  int r_ = 0;
  Eigen::MatrixXd A_, B_, C_;
  std::vector<int> pair_;  // r x r symmetric table of pair indices
  // The symmetric matrix S(p, k) = C_ijlm, p = pair(i, j), k = pair(l, m) (C_ without the pair
  // weights), as packed upper rows: npairs (npairs + 1) / 2 entries (kStVK only).
  std::vector<double> cubic_packed_;
};

}  // namespace contactlab
