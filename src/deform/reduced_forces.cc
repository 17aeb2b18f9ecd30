// Exact reduced StVK polynomials (Barbič & James 2005, sec. 3).
#include "deform/reduced_forces.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "deform/symmetric_packed_product.h"
#include "util/error.h"
#include "util/progress.h"

namespace contactlab {
namespace {

// Symmetric 3x3 as a Voigt 6-vector (xx, yy, zz, xy, yz, zx).
using Voigt = Eigen::Matrix<double, 6, 1>;
Voigt ToVoigt(const Eigen::Matrix3d& S) {
  Voigt v;
  v << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(2, 0);
  return v;
}

}  // namespace

ReducedInternalForces::ReducedInternalForces(ReducedModelKind kind, Eigen::MatrixXd A, Eigen::MatrixXd B,
                                             Eigen::MatrixXd C, const std::string& where)
    : kind_(kind), r_(int(A.rows())), A_(std::move(A)), B_(std::move(B)), C_(std::move(C)) {
  if (r_ < 1 || r_ > kMaxReducedModes || A_.cols() != r_) {
    Fail(where, "the linear coefficient matrix must be r x r with 1 <= r <= " + std::to_string(kMaxReducedModes));
  }
  const int np = num_pairs();
  if (kind_ == ReducedModelKind::kStVK) {
    if (B_.rows() != np || B_.cols() != r_ || C_.rows() != np || C_.cols() != np) {
      Fail(where, "the quadratic/cubic coefficient sizes do not match r = " + std::to_string(r_));
    }
  } else if (kind_ != ReducedModelKind::kLinear) {
    Fail(where, "unknown reduced model kind " + std::to_string(int(kind_)));
  }
  if (!A_.allFinite() || !B_.allFinite() || !C_.allFinite()) Fail(where, "a coefficient is not finite");
  BuildPairTable();
  if (kind_ == ReducedModelKind::kStVK) {
    // C must be the symmetric S with the pair weights on its columns (Compute makes it so).
    const double tolerance = 1e-9 * C_.cwiseAbs().maxCoeff();
    for (int i = 0; i < r_; ++i)
      for (int j = i; j < r_; ++j)
        for (int l = 0; l < r_; ++l)
          for (int m = l; m < r_; ++m) {
            const int p = Pair(i, j), k = Pair(l, m);
            if (std::abs(C_(p, k) / (l == m ? 1.0 : 2.0) - C_(k, p) / (i == j ? 1.0 : 2.0)) > tolerance) {
              Fail(where, "the cubic coefficients are not symmetric (entry " + std::to_string(p) + ", " +
                              std::to_string(k) + ")");
            }
          }
    PackCubic();
  }
}

void ReducedInternalForces::PackCubic() {
  // Row p of the upper triangle, S(p, k) = C(p, k) / weight(k) for k >= p (exact: the weights
  // are 1 and 2).
  const int np = num_pairs();
  cubic_packed_.assign(PackedUpperSize(np), 0.0);
  for (int l = 0, k = 0; l < r_; ++l)
    for (int m = l; m < r_; ++m, ++k) {
      const double weight = l == m ? 1.0 : 2.0;
      for (int p = 0; p <= k; ++p) cubic_packed_[PackedUpperRowStart(p, np) + (k - p)] = C_(p, k) / weight;
    }
}

void ReducedInternalForces::BuildPairTable() {
  pair_.assign(std::size_t(r_) * r_, 0);
  int p = 0;
  for (int i = 0; i < r_; ++i)
    for (int j = i; j < r_; ++j, ++p) pair_[i * r_ + j] = pair_[j * r_ + i] = p;
}

ReducedInternalForces ReducedInternalForces::Compute(const StVKFem& fem, const Eigen::MatrixXd& U,
                                                     ReducedModelKind kind, Progress* progress) {
  const int r = int(U.cols());
  if (r < 1 || r > kMaxReducedModes) {
    Fail("reduced forces", "r must be in [1, " + std::to_string(kMaxReducedModes) + "], got " + std::to_string(r));
  }
  if (U.rows() != fem.num_dofs()) Fail("reduced forces", "the basis row count differs from the FEM DOF count");
  ReducedInternalForces out;
  out.kind_ = kind;
  out.r_ = r;
  out.BuildPairTable();
  const int np = out.num_pairs();
  const bool cubic = kind == ReducedModelKind::kStVK;

  // <A, B> = mu A:B + lambda/2 trA trB in Voigt form, D = L L^T.
  const double mu = fem.material().mu(), lambda = fem.material().lambda();
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
  D.diagonal() << mu, mu, mu, 2 * mu, 2 * mu, 2 * mu;
  D.topLeftCorner<3, 3>().array() += 0.5 * lambda;
  const Eigen::Matrix<double, 6, 6> Lt = D.llt().matrixU();  // L^T

  // Accumulate A = 2 sum V eps^T D eps, Ct = sum V eps^T D S, P = sum V S^T D S over batches
  // of elements stacked as rows X = sqrt(V) L^T eps, Y = sqrt(V) L^T S.
  const int batch = 128;
  Eigen::MatrixXd X(6 * batch, r), Y(cubic ? 6 * batch : 0, cubic ? np : 0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(r, r);
  Eigen::MatrixXd Ct = Eigen::MatrixXd::Zero(cubic ? r : 0, cubic ? np : 0);
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(cubic ? np : 0, cubic ? np : 0);
  std::vector<Eigen::Matrix3d> G(r);
  const int nt = fem.num_tets();
  for (int t0 = 0; t0 < nt; t0 += batch) {
    const int nb = std::min(batch, nt - t0);
    X.setZero();
    if (cubic) Y.setZero();
    for (int b = 0; b < nb; ++b) {
      const int t = t0 + b;
      const auto& grad = fem.shape_gradients(t);
      const Eigen::Vector4i& v = fem.tet(t);
      const double sv = std::sqrt(fem.volume(t));
      for (int j = 0; j < r; ++j) {
        G[j].setZero();
        for (int a = 0; a < 4; ++a) G[j].noalias() += U.block<3, 1>(3 * v[a], j) * grad.row(a);
        X.block<6, 1>(6 * b, j) = sv * Lt * ToVoigt(0.5 * (G[j] + G[j].transpose()));
      }
      if (!cubic) continue;
      for (int k = 0; k < r; ++k)
        for (int l = k; l < r; ++l) {
          const Eigen::Matrix3d GkGl = G[k].transpose() * G[l];
          Y.block<6, 1>(6 * b, out.Pair(k, l)) = sv * Lt * ToVoigt(0.5 * (GkGl + GkGl.transpose()));
        }
    }
    const auto Xb = X.topRows(6 * nb);
    A.noalias() += 2 * Xb.transpose() * Xb;
    if (cubic) {
      const auto Yb = Y.topRows(6 * nb);
      Ct.noalias() += Xb.transpose() * Yb;
      P.selfadjointView<Eigen::Lower>().rankUpdate(Yb.transpose());
    }
    if (progress) progress->Advance(nb);
  }
  out.A_ = 0.5 * (A + A.transpose());
  if (!cubic) return out;
  P = P.selfadjointView<Eigen::Lower>();

  // B_ijl = c_ijl + c_jli + c_lij with c_jkl = Ct(j, pair(k, l)).
  out.B_.resize(np, r);
  for (int i = 0; i < r; ++i)
    for (int j = i; j < r; ++j)
      for (int l = 0; l < r; ++l) {
        out.B_(out.Pair(i, j), l) = Ct(i, out.Pair(j, l)) + Ct(j, out.Pair(l, i)) + Ct(l, out.Pair(i, j));
      }
  // C_ijlm = (P[ij,lm] + P[il,jm] + P[im,jl]) / 3, weighted by 2 for l < m.
  out.C_.resize(np, np);
  for (int i = 0; i < r; ++i)
    for (int j = i; j < r; ++j)
      for (int l = 0; l < r; ++l)
        for (int m = l; m < r; ++m) {
          const double c = (P(out.Pair(i, j), out.Pair(l, m)) + P(out.Pair(i, l), out.Pair(j, m)) +
                            P(out.Pair(i, m), out.Pair(j, l))) / 3.0;
          out.C_(out.Pair(i, j), out.Pair(l, m)) = c * (l == m ? 1.0 : 2.0);
        }
  out.PackCubic();
  return out;
}

ReducedInternalForces::Workspace ReducedInternalForces::MakeWorkspace() const {
  Workspace ws;
  const int np = kind_ == ReducedModelKind::kStVK ? num_pairs() : 0;
  ws.w = Eigen::VectorXd::Zero(np);
  ws.kb = Eigen::VectorXd::Zero(np);
  ws.kc = Eigen::VectorXd::Zero(np);
  ws.T = ReducedMatrix::Zero(r_, r_);
  return ws;
}

void ReducedInternalForces::Evaluate(const ReducedVector& q, ReducedVector* f, ReducedMatrix* K,
                                     Workspace* ws) const {
  const int r = r_;
  if (kind_ == ReducedModelKind::kLinear) {
    if (f) f->noalias() = A_ * q;
    if (K) *K = A_;
    return;
  }
  // Weighted monomials w_(lm) = q_l q_m (l == m) or 2 q_l q_m (l < m), in pair order: with
  // them Kc = S w for the symmetric S (the same products as C (q_l q_m), scaled exactly).
  double* w = ws->w.data();
  for (int l = 0, p = 0; l < r; ++l) {
    w[p++] = q[l] * q[l];
    for (int m = l + 1; m < r; ++m, ++p) w[p] = 2 * (q[l] * q[m]);
  }
  // Kb = B q (npairs x r, 3 r^3 / 2 multiply-adds at r = 15: 1800) and Kc = S w (npairs^2:
  // 14400), in pair order.
  ws->kb.noalias() = B_ * q;
  SymmetricPackedProduct(cubic_packed_.data(), num_pairs(), w, ws->kc.data());
  // Unpack into the secant matrix T = A + Kb + Kc (f = T q) and the tangent stiffness
  // K = A + 2 Kb + 3 Kc, one pass over the upper triangle.
  const double* kb = ws->kb.data();
  const double* kc = ws->kc.data();
  if (f) {
    ReducedMatrix& T = ws->T;
    for (int i = 0, p = 0; i < r; ++i)
      for (int j = i; j < r; ++j, ++p) T(i, j) = T(j, i) = A_(i, j) + kb[p] + kc[p];
    f->noalias() = T * q;
  }
  if (K) {
    K->resize(r, r);
    for (int i = 0, p = 0; i < r; ++i)
      for (int j = i; j < r; ++j, ++p) (*K)(i, j) = (*K)(j, i) = A_(i, j) + 2 * kb[p] + 3 * kc[p];
  }
}

double ReducedInternalForces::Energy(const ReducedVector& q, Workspace* ws) const {
  if (kind_ == ReducedModelKind::kLinear) {
    ReducedVector Aq(r_);  // bounded size: on the stack (A_ * q alone makes a heap temporary)
    Aq.noalias() = A_ * q;
    return 0.5 * q.dot(Aq);
  }
  Evaluate(q, nullptr, nullptr, ws);  // fills kb, kc
  // W = q^T (A / 2 + Kb / 3 + Kc / 4) q.
  ReducedMatrix& T = ws->T;
  for (int i = 0, p = 0; i < r_; ++i)
    for (int j = i; j < r_; ++j, ++p) T(i, j) = T(j, i) = 0.5 * A_(i, j) + ws->kb[p] / 3.0 + ws->kc[p] / 4.0;
  return q.dot(T * q);
}

}  // namespace contactlab
