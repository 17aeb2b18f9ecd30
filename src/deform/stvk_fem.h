// Full finite-element St. Venant-Kirchhoff model on linear tetrahedra: mass, linear stiffness,
// nonlinear internal forces and tangent stiffness (Barbič & James 2008, sec. 4.1: the reduced
// model is reduced StVK; Barbič & James 2005 sec. 3). Displacements u are 3 #V vectors
// (x, y, z per vertex), metres; forces newtons.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "deform/tet_mesh.h"

namespace contactlab {

struct StVKMaterial {
  double youngs_modulus = 1e6;  // E, pascals (> 0)
  double poisson_ratio = 0.45;  // nu, in (-1, 0.5)
  double density = 1000;        // rho, kg / m^3 (> 0)

  double mu() const { return youngs_modulus / (2 * (1 + poisson_ratio)); }
  double lambda() const {
    return youngs_modulus * poisson_ratio / ((1 + poisson_ratio) * (1 - 2 * poisson_ratio));
  }
  // Throws Error naming WHERE when E <= 0, nu outside (-1, 0.5), or rho <= 0.
  void Validate(const std::string& where) const;
};

enum class MassKind { kLumped, kConsistent };

using SparseMatrixd = Eigen::SparseMatrix<double>;

class StVKFem {
 public:
  // Precomputes shape-function gradients and volumes. Throws Error naming WHERE for a bad
  // material, an empty mesh or a degenerate (zero-volume) tet.
  StVKFem(const TetMesh& mesh, const StVKMaterial& material, const std::string& where = "FEM model");

  int num_dofs() const { return 3 * num_vertices_; }
  int num_tets() const { return int(volume_.size()); }
  const StVKMaterial& material() const { return material_; }
  const Eigen::Vector4i& tet(int t) const { return tets_[t]; }
  double volume(int t) const { return volume_[t]; }
  // Gradients of the four shape functions of tet T (rows 0..3), 1/metres.
  const Eigen::Matrix<double, 4, 3>& shape_gradients(int t) const { return grad_[t]; }

  // 3#V x 3#V mass matrix, kg.
  SparseMatrixd MassMatrix(MassKind kind) const;
  // Stiffness at u = 0 (small-strain linear elasticity), N/m.
  SparseMatrixd LinearStiffness() const { return TangentStiffness(Eigen::VectorXd::Zero(num_dofs())); }
  // Internal elastic forces f(u) = dW/du (restoring force is -f), 3#V.
  Eigen::VectorXd InternalForces(const Eigen::VectorXd& u) const;
  // Tangent stiffness df/du at U (symmetric), 3#V x 3#V.
  SparseMatrixd TangentStiffness(const Eigen::VectorXd& u) const;
  // Elastic energy W(u), joules.
  double Energy(const Eigen::VectorXd& u) const;
  // The second directional derivative of f at u = 0 along A and B: (H : a) b, the right-hand
  // side of the modal-derivative equations, 3#V.
  Eigen::VectorXd ForceHessianAtRest(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

  // Displacement gradient of tet T for displacement u (3 #V): G = sum_a u_a grad(N_a)^T.
  Eigen::Matrix3d DisplacementGradient(int t, const double* u) const;

 private:
  Eigen::Matrix3d SecondPk(const Eigen::Matrix3d& strain) const;

  StVKMaterial material_;
  int num_vertices_ = 0;
  std::vector<Eigen::Vector4i> tets_;
  std::vector<Eigen::Matrix<double, 4, 3>> grad_;
  std::vector<double> volume_;
};

}  // namespace contactlab
