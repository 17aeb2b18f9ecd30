// Modal derivatives and mass-PCA (Barbič & James 2005, sec. 4).
#include "deform/nonlinear_basis.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <cmath>

#include "util/error.h"
#include "util/progress.h"

namespace contactlab {

int DefaultLinearModeCount(int r) {
  int m = 1;
  while (m < r && m + m * (m + 1) / 2 < 2 * r) ++m;
  return m;
}

Eigen::MatrixXd ComputeModalDerivatives(const StVKFem& fem, const TetMesh& mesh, const SparseMatrixd& K,
                                        const SparseMatrixd& M, const std::vector<std::uint8_t>& fixed,
                                        const LinearModes& modes, Progress* progress,
                                        const std::string& where) {
  const int m = int(modes.shapes.cols());
  const int ndof = int(K.rows());
  const std::vector<int> free = FreeDofs(fixed);
  const bool free_body = int(free.size()) == ndof;
  Eigen::MatrixXd psi = Eigen::MatrixXd::Zero(ndof, m * (m + 1) / 2);

  if (!free_body) {
    // Anchored: K restricted to the free DOFs is positive definite.
    const SparseMatrixd Kf = RestrictToDofs(K, free);
    Eigen::SimplicialLDLT<SparseMatrixd> ldlt(Kf);
    if (ldlt.info() != Eigen::Success) Fail(where, "the stiffness matrix of the free DOFs is not factorisable");
    Eigen::VectorXd rhs(free.size());
    int col = 0;
    for (int i = 0; i < m; ++i)
      for (int j = i; j < m; ++j, ++col) {
        const Eigen::VectorXd h = fem.ForceHessianAtRest(modes.shapes.col(i), modes.shapes.col(j));
        for (std::size_t k = 0; k < free.size(); ++k) rhs[k] = -h[free[k]];
        const Eigen::VectorXd x = ldlt.solve(rhs);
        for (std::size_t k = 0; k < free.size(); ++k) psi(free[k], col) = x[k];
        if (progress) progress->Advance();
      }
    return psi;
  }

  // Free body: solve [K  M R; (M R)^T 0] [psi; mu] = [P b; 0], P b = b - M R R^T b.
  const Eigen::MatrixXd R = RigidModes(mesh, M);
  const Eigen::MatrixXd MR = M * R;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(K.nonZeros() + 12 * ndof);
  for (int k = 0; k < K.outerSize(); ++k)
    for (SparseMatrixd::InnerIterator it(K, k); it; ++it) trip.emplace_back(it.row(), it.col(), it.value());
  for (int i = 0; i < ndof; ++i)
    for (int c = 0; c < 6; ++c)
      if (MR(i, c) != 0) {
        trip.emplace_back(i, ndof + c, MR(i, c));
        trip.emplace_back(ndof + c, i, MR(i, c));
      }
  SparseMatrixd A(ndof + 6, ndof + 6);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseLU<SparseMatrixd> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) Fail(where, "the constrained stiffness system of the free body is singular");
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(ndof + 6);
  int col = 0;
  for (int i = 0; i < m; ++i)
    for (int j = i; j < m; ++j, ++col) {
      const Eigen::VectorXd b = -fem.ForceHessianAtRest(modes.shapes.col(i), modes.shapes.col(j));
      rhs.head(ndof) = b - MR * (R.transpose() * b);
      psi.col(col) = lu.solve(rhs).head(ndof);
      if (progress) progress->Advance();
    }
  return psi;
}

Eigen::MatrixXd ScaledModesAndDerivatives(const LinearModes& modes, const Eigen::MatrixXd& derivatives,
                                          const SparseMatrixd& M) {
  const int m = int(modes.shapes.cols());
  Eigen::MatrixXd X(modes.shapes.rows(), m + derivatives.cols());
  const double l0 = modes.eigenvalues[0];
  const auto mass_normalised = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const double n2 = v.dot(M * v);
    return n2 > 0 ? Eigen::VectorXd(v / std::sqrt(n2)) : v;
  };
  for (int i = 0; i < m; ++i) X.col(i) = mass_normalised(modes.shapes.col(i)) * (l0 / modes.eigenvalues[i]);
  int col = 0;
  for (int i = 0; i < m; ++i)
    for (int j = i; j < m && col < derivatives.cols(); ++j, ++col) {
      X.col(m + col) = mass_normalised(derivatives.col(col)) * (l0 * l0 / (modes.eigenvalues[i] * modes.eigenvalues[j]));
    }
  return X;
}

Eigen::MatrixXd MassPca(const Eigen::MatrixXd& X, const SparseMatrixd& M, int r, const std::string& where) {
  if (r < 1) Fail(where, "the basis size r must be >= 1");
  if (r > X.cols()) {
    Fail(where, "r = " + std::to_string(r) + " exceeds the " + std::to_string(X.cols()) + " candidate vectors");
  }
  // Gram matrix in the M inner product; its eigenvectors give the principal directions.
  const Eigen::MatrixXd MX = M * X;
  const Eigen::MatrixXd G = X.transpose() * MX;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  const Eigen::VectorXd s2 = eig.eigenvalues();  // ascending
  const int k = int(X.cols());
  const double largest = s2[k - 1];
  Eigen::MatrixXd U(X.rows(), r);
  for (int c = 0; c < r; ++c) {
    const double sv = s2[k - 1 - c];
    if (!(sv > 1e-12 * largest)) {  // singular value ratio 1e-6
      Fail(where, "r = " + std::to_string(r) + " exceeds the rank (" + std::to_string(c) +
                      ") of the modes and modal derivatives; use fewer modes or a finer mesh");
    }
    U.col(c) = X * eig.eigenvectors().col(k - 1 - c) / std::sqrt(sv);
  }
  // Re-orthonormalise in M (modified Gram-Schmidt) to clean up round-off.
  for (int j = 0; j < r; ++j) {
    for (int i = 0; i < j; ++i) U.col(j) -= U.col(i).dot(M * U.col(j)) * U.col(i);
    U.col(j) /= std::sqrt(U.col(j).dot(M * U.col(j)));
  }
  return U;
}

}  // namespace contactlab
