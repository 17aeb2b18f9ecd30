// Linear modal analysis K phi = lambda M phi for the lowest vibration modes (Barbič & James
// 2008, sec. 1.1: classic linear modal models; the first stage of the reduced StVK basis of
// Barbič & James 2005, sec. 4). Solved with Spectra's shift-invert generalized solver.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "deform/stvk_fem.h"

namespace contactlab {

struct LinearModes {
  Eigen::MatrixXd shapes;       // 3#V x m mode shapes, mass-orthonormal, zero on fixed vertices
  Eigen::VectorXd eigenvalues;  // m eigenvalues lambda = omega^2 (1/s^2), ascending
  double max_relative_residual = 0;  // max_i |K phi - lambda M phi| / |lambda M phi|
};

// The NUM_MODES lowest non-rigid modes of (K, M). FIXED flags vertices whose three DOFs are
// removed (anchored body); when no vertex is fixed the body is free and its six rigid modes
// (eigenvalue ~0) are computed and dropped. Throws Error naming WHERE when NUM_MODES < 1,
// when the mesh has too few free DOFs for NUM_MODES, or when the eigensolver fails.
LinearModes ComputeLinearModes(const SparseMatrixd& K, const SparseMatrixd& M,
                               const std::vector<std::uint8_t>& fixed, int num_modes,
                               const std::string& where = "modal analysis");

// The six rigid-body modes (3 translations, 3 infinitesimal rotations about the centre of
// mass) of a free mesh, mass-orthonormal, 3#V x 6.
Eigen::MatrixXd RigidModes(const TetMesh& mesh, const SparseMatrixd& M);

// Free-DOF selection: index of each kept DOF (3 per free vertex), in order.
std::vector<int> FreeDofs(const std::vector<std::uint8_t>& fixed);
// P^T A P restricted to the DOFs in FREE.
SparseMatrixd RestrictToDofs(const SparseMatrixd& A, const std::vector<int>& free);

}  // namespace contactlab
