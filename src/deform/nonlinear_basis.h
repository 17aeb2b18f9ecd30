// The reduced nonlinear basis of Barbič & James 2005 (sec. 4), used by Barbič & James 2008
// (sec. 4.1): linear modes plus their modal derivatives, scaled by eigenvalue ratios, then
// compressed by mass-weighted PCA to r mass-orthonormal vectors.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "deform/modal_analysis.h"
#include "deform/stvk_fem.h"

namespace contactlab {

class Progress;

// Modal derivatives Psi_ij (i <= j, pair order (0,0), (0,1), ..., (1,1), ...) of the linear
// MODES: K Psi_ij = -(H : phi_i) phi_j, with fixed DOFs removed (anchored body). For a free
// body (no fixed vertex) the right-hand side is projected off the rigid modes R and Psi is
// made mass-orthogonal to them. Returns 3#V x m(m+1)/2. Throws Error naming WHERE when the
// linear solve fails.
Eigen::MatrixXd ComputeModalDerivatives(const StVKFem& fem, const TetMesh& mesh, const SparseMatrixd& K,
                                        const SparseMatrixd& M, const std::vector<std::uint8_t>& fixed,
                                        const LinearModes& modes, Progress* progress,
                                        const std::string& where = "modal derivatives");

// Mass-weighted PCA: the R dominant directions of the columns of X in the M inner product,
// returned as a 3#V x R matrix U with U^T M U = I. Throws Error naming WHERE when X has rank
// below R (relative singular value < 1e-6).
Eigen::MatrixXd MassPca(const Eigen::MatrixXd& X, const SparseMatrixd& M, int r,
                        const std::string& where = "mass PCA");

// Columns [phi_i * lambda_0/lambda_i, Psi_ij * lambda_0^2/(lambda_i lambda_j)], each first
// normalised to unit mass norm (Barbič & James 2005's scaling).
Eigen::MatrixXd ScaledModesAndDerivatives(const LinearModes& modes, const Eigen::MatrixXd& derivatives,
                                          const SparseMatrixd& M);

// Smallest m with m linear modes + m(m+1)/2 derivatives >= 2 R (at most R).
int DefaultLinearModeCount(int r);

}  // namespace contactlab
