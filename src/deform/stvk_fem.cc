// Full St. Venant-Kirchhoff FEM on linear tetrahedra (Barbič & James 2005, sec. 3).
#include "deform/stvk_fem.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "util/error.h"

namespace contactlab {

void StVKMaterial::Validate(const std::string& where) const {
  if (!(youngs_modulus > 0) || !std::isfinite(youngs_modulus)) {
    Fail(where, "Young's modulus E must be positive and finite, got " + std::to_string(youngs_modulus));
  }
  if (!(poisson_ratio > -1 && poisson_ratio < 0.5)) {
    Fail(where, "Poisson's ratio nu must lie in (-1, 0.5), got " + std::to_string(poisson_ratio));
  }
  if (!(density > 0) || !std::isfinite(density)) {
    Fail(where, "density rho must be positive and finite, got " + std::to_string(density));
  }
}

StVKFem::StVKFem(const TetMesh& mesh, const StVKMaterial& material, const std::string& where)
    : material_(material), num_vertices_(mesh.num_vertices()), tets_(mesh.tets) {
  material.Validate(where);
  if (mesh.tets.empty()) Fail(where, "the simulation mesh has no tets");
  grad_.resize(tets_.size());
  volume_.resize(tets_.size());
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const Eigen::Vector4i& v = tets_[t];
    for (int a = 0; a < 4; ++a) {
      if (v[a] < 0 || v[a] >= num_vertices_) Fail(where, "tet " + std::to_string(t) + " has an out-of-range vertex index");
    }
    Eigen::Matrix3d Dm;
    for (int c = 0; c < 3; ++c) Dm.col(c) = mesh.vertices[v[c + 1]] - mesh.vertices[v[0]];
    const double det = Dm.determinant();
    const double scale = Dm.colwise().norm().maxCoeff();
    if (!(std::abs(det) > 1e-12 * scale * scale * scale)) {
      Fail(where, "tet " + std::to_string(t) + " is degenerate (zero volume)");
    }
    volume_[t] = std::abs(det) / 6.0;
    const Eigen::Matrix3d inv = Dm.inverse();
    grad_[t].row(1) = inv.row(0);
    grad_[t].row(2) = inv.row(1);
    grad_[t].row(3) = inv.row(2);
    grad_[t].row(0) = -(inv.row(0) + inv.row(1) + inv.row(2));
  }
}

Eigen::Matrix3d StVKFem::DisplacementGradient(int t, const double* u) const {
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 4; ++a) {
    const Eigen::Map<const Eigen::Vector3d> ua(u + 3 * tets_[t][a]);
    G.noalias() += ua * grad_[t].row(a);
  }
  return G;
}

Eigen::Matrix3d StVKFem::SecondPk(const Eigen::Matrix3d& E) const {
  return 2 * material_.mu() * E + material_.lambda() * E.trace() * Eigen::Matrix3d::Identity();
}

SparseMatrixd StVKFem::MassMatrix(MassKind kind) const {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(tets_.size() * (kind == MassKind::kLumped ? 12 : 48));
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const double m = material_.density * volume_[t];
    for (int a = 0; a < 4; ++a) {
      if (kind == MassKind::kLumped) {
        for (int c = 0; c < 3; ++c) trip.emplace_back(3 * tets_[t][a] + c, 3 * tets_[t][a] + c, m / 4);
        continue;
      }
      for (int b = 0; b < 4; ++b) {
        const double mab = m / 20 * (a == b ? 2 : 1);
        for (int c = 0; c < 3; ++c) trip.emplace_back(3 * tets_[t][a] + c, 3 * tets_[t][b] + c, mab);
      }
    }
  }
  SparseMatrixd M(num_dofs(), num_dofs());
  M.setFromTriplets(trip.begin(), trip.end());
  return M;
}

Eigen::VectorXd StVKFem::InternalForces(const Eigen::VectorXd& u) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(num_dofs());
  for (int t = 0; t < num_tets(); ++t) {
    const Eigen::Matrix3d G = DisplacementGradient(t, u.data());
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + G;
    const Eigen::Matrix3d E = 0.5 * (G + G.transpose() + G.transpose() * G);
    const Eigen::Matrix3d P = F * SecondPk(E);
    for (int a = 0; a < 4; ++a) {
      f.segment<3>(3 * tets_[t][a]) += volume_[t] * P * grad_[t].row(a).transpose();
    }
  }
  return f;
}

double StVKFem::Energy(const Eigen::VectorXd& u) const {
  double w = 0;
  const double mu = material_.mu(), lambda = material_.lambda();
  for (int t = 0; t < num_tets(); ++t) {
    const Eigen::Matrix3d G = DisplacementGradient(t, u.data());
    const Eigen::Matrix3d E = 0.5 * (G + G.transpose() + G.transpose() * G);
    w += volume_[t] * (mu * E.squaredNorm() + 0.5 * lambda * E.trace() * E.trace());
  }
  return w;
}

SparseMatrixd StVKFem::TangentStiffness(const Eigen::VectorXd& u) const {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(tets_.size() * 144);
  for (int t = 0; t < num_tets(); ++t) {
    const Eigen::Matrix3d G = DisplacementGradient(t, u.data());
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + G;
    const Eigen::Matrix3d E = 0.5 * (G + G.transpose() + G.transpose() * G);
    const Eigen::Matrix3d S = SecondPk(E);
    // Column (b, d): dF = e_d grad(N_b)^T; dP = dF S + F dS(sym(F^T dF)).
    for (int b = 0; b < 4; ++b) {
      for (int d = 0; d < 3; ++d) {
        Eigen::Matrix3d dF = Eigen::Matrix3d::Zero();
        dF.row(d) = grad_[t].row(b);
        const Eigen::Matrix3d FtdF = F.transpose() * dF;
        const Eigen::Matrix3d dP = dF * S + F * SecondPk(0.5 * (FtdF + FtdF.transpose()));
        for (int a = 0; a < 4; ++a) {
          const Eigen::Vector3d col = volume_[t] * dP * grad_[t].row(a).transpose();
          for (int c = 0; c < 3; ++c) trip.emplace_back(3 * tets_[t][a] + c, 3 * tets_[t][b] + d, col[c]);
        }
      }
    }
  }
  SparseMatrixd K(num_dofs(), num_dofs());
  K.setFromTriplets(trip.begin(), trip.end());
  return K;
}

Eigen::VectorXd StVKFem::ForceHessianAtRest(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  // Mixed second derivative of P(G) at G = 0: Ga S(eps_b) + Gb S(eps_a) + S(sym(Ga^T Gb)).
  Eigen::VectorXd h = Eigen::VectorXd::Zero(num_dofs());
  for (int t = 0; t < num_tets(); ++t) {
    const Eigen::Matrix3d Ga = DisplacementGradient(t, a.data());
    const Eigen::Matrix3d Gb = DisplacementGradient(t, b.data());
    const Eigen::Matrix3d GaGb = Ga.transpose() * Gb;
    const Eigen::Matrix3d P2 = Ga * SecondPk(0.5 * (Gb + Gb.transpose())) +
                               Gb * SecondPk(0.5 * (Ga + Ga.transpose())) +
                               SecondPk(0.5 * (GaGb + GaGb.transpose()));
    for (int v = 0; v < 4; ++v) {
      h.segment<3>(3 * tets_[t][v]) += volume_[t] * P2 * grad_[t].row(v).transpose();
    }
  }
  return h;
}

}  // namespace contactlab
