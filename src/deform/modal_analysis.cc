// Shift-invert generalized eigenanalysis with Spectra (Barbič & James 2005, sec. 4).
#include "deform/modal_analysis.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Spectra/SymGEigsShiftSolver.h>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "util/error.h"

namespace contactlab {
namespace {

// y = (K - sigma M)^{-1} x by a sparse LDL^T factorisation: K - sigma M is positive definite
// for sigma below the lowest eigenvalue, which is how this op is used.
class ShiftInvertLdlt {
 public:
  using Scalar = double;
  ShiftInvertLdlt(const SparseMatrixd& K, const SparseMatrixd& M) : K_(K), M_(M) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    const SparseMatrixd A = K_ - sigma * M_;
    ldlt_.compute(A);
    if (ldlt_.info() != Eigen::Success) throw std::runtime_error("K - sigma M is not factorisable");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y = ldlt_.solve(x);
  }

 private:
  const SparseMatrixd& K_;
  const SparseMatrixd& M_;
  Eigen::SimplicialLDLT<SparseMatrixd> ldlt_;
};

}  // namespace

std::vector<int> FreeDofs(const std::vector<std::uint8_t>& fixed) {
  std::vector<int> free;
  free.reserve(3 * fixed.size());
  for (std::size_t v = 0; v < fixed.size(); ++v)
    if (!fixed[v])
      for (int c = 0; c < 3; ++c) free.push_back(int(3 * v + c));
  return free;
}

SparseMatrixd RestrictToDofs(const SparseMatrixd& A, const std::vector<int>& free) {
  std::vector<int> map(A.rows(), -1);
  for (std::size_t i = 0; i < free.size(); ++i) map[free[i]] = int(i);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(A.nonZeros());
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrixd::InnerIterator it(A, k); it; ++it) {
      const int i = map[it.row()], j = map[it.col()];
      if (i >= 0 && j >= 0) trip.emplace_back(i, j, it.value());
    }
  SparseMatrixd B(Eigen::Index(free.size()), Eigen::Index(free.size()));
  B.setFromTriplets(trip.begin(), trip.end());
  return B;
}

Eigen::MatrixXd RigidModes(const TetMesh& mesh, const SparseMatrixd& M) {
  const int n = mesh.num_vertices();
  const Eigen::VectorXd mass_diag = M * Eigen::VectorXd::Ones(3 * n);  // row sums
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  double total = 0;
  for (int v = 0; v < n; ++v) {
    c += mass_diag[3 * v] * mesh.vertices[v];
    total += mass_diag[3 * v];
  }
  c /= total;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 6);
  for (int v = 0; v < n; ++v) {
    const Eigen::Vector3d p = mesh.vertices[v] - c;
    for (int a = 0; a < 3; ++a) {
      R(3 * v + a, a) = 1;
      const Eigen::Vector3d w = Eigen::Vector3d::Unit(a).cross(p);
      R.block<3, 1>(3 * v, 3 + a) = w;
    }
  }
  // Mass-orthonormalise (modified Gram-Schmidt in the M inner product).
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < j; ++i) R.col(j) -= R.col(i).dot(M * R.col(j)) * R.col(i);
    R.col(j) /= std::sqrt(R.col(j).dot(M * R.col(j)));
  }
  return R;
}

LinearModes ComputeLinearModes(const SparseMatrixd& K, const SparseMatrixd& M,
                               const std::vector<std::uint8_t>& fixed, int num_modes,
                               const std::string& where) {
  if (num_modes < 1) Fail(where, "the number of modes must be >= 1");
  const std::vector<int> free = FreeDofs(fixed);
  const bool free_body = free.size() == std::size_t(K.rows());
  const int rigid = free_body ? 6 : 0;
  const int nev = num_modes + rigid;
  const int n = int(free.size());
  if (nev + 2 > n) {
    Fail(where, std::to_string(num_modes) + " modes were asked for but the simulation mesh has only " +
                    std::to_string(n) + " free degrees of freedom" + (free_body ? " (6 of them rigid)" : "") +
                    "; use fewer modes or more cells");
  }
  const SparseMatrixd Kf = RestrictToDofs(K, free);
  const SparseMatrixd Mf = RestrictToDofs(M, free);

  // Shift: 0 for an anchored body (K positive definite), slightly negative for a free one.
  const double scale = Kf.diagonal().sum() / Mf.diagonal().sum();
  const double sigma = free_body ? -1e-6 * scale : 0.0;
  ShiftInvertLdlt op(Kf, Mf);
  Spectra::SparseSymMatProd<double> bop(Mf);
  const int ncv = std::min(n, std::max(2 * nev + 1, nev + 20));
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  try {
    Spectra::SymGEigsShiftSolver<ShiftInvertLdlt, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(op, bop, nev, ncv, sigma);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, 2000, 1e-12);
    if (solver.info() != Spectra::CompInfo::Successful) {
      Fail(where, "the eigensolver did not converge (" + std::to_string(nev) + " modes, " + std::to_string(n) + " DOFs)");
    }
    values = solver.eigenvalues();
    vectors = solver.eigenvectors();
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const Error*>(&e)) throw;
    Fail(where, std::string("the eigensolver failed: ") + e.what());
  }

  // Ascending order; drop the rigid modes of a free body.
  std::vector<int> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return values[a] < values[b]; });
  LinearModes modes;
  modes.shapes = Eigen::MatrixXd::Zero(K.rows(), num_modes);
  modes.eigenvalues.resize(num_modes);
  for (int i = 0; i < num_modes; ++i) {
    const int src = order[rigid + i];
    Eigen::VectorXd phi = vectors.col(src);
    phi /= std::sqrt(phi.dot(Mf * phi));
    const double lambda = values[src];
    if (!(lambda > 0)) Fail(where, "mode " + std::to_string(i) + " has a non-positive eigenvalue; is the body anchored enough?");
    const double res = (Kf * phi - lambda * (Mf * phi)).norm() / (lambda * (Mf * phi)).norm();
    modes.max_relative_residual = std::max(modes.max_relative_residual, res);
    for (int k = 0; k < n; ++k) modes.shapes(free[k], i) = phi[k];
    modes.eigenvalues[i] = lambda;
  }
  return modes;
}

}  // namespace contactlab
