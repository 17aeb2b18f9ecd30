#include "deform/stvk_fem.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "beam_fixture.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BeamMaterial;
using testing::MakeBeam;

TEST(StVKFem, InternalForceIsTheEnergyGradient) {
  const TetMesh mesh = MakeBeam(TetSplit::kSix, 4);
  const StVKFem fem(mesh, BeamMaterial());
  std::mt19937 rng(1);
  const Eigen::VectorXd u = testing::RandomVector(fem.num_dofs(), 0.05, &rng);
  const Eigen::VectorXd f = fem.InternalForces(u);
  const double e = 1e-6;
  for (int i = 0; i < fem.num_dofs(); i += 7) {
    Eigen::VectorXd du = Eigen::VectorXd::Zero(fem.num_dofs());
    du[i] = e;
    const double fd = (fem.Energy(u + du) - fem.Energy(u - du)) / (2 * e);
    EXPECT_NEAR(f[i], fd, 1e-6 * f.cwiseAbs().maxCoeff()) << "dof " << i;
  }
}

TEST(StVKFem, TangentStiffnessMatchesFiniteDifferencesOfForces) {
  const TetMesh mesh = MakeBeam(TetSplit::kFive, 4);
  const StVKFem fem(mesh, BeamMaterial());
  std::mt19937 rng(2);
  const Eigen::VectorXd u = testing::RandomVector(fem.num_dofs(), 0.05, &rng);
  const Eigen::MatrixXd K = Eigen::MatrixXd(fem.TangentStiffness(u));
  EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm());
  const Eigen::VectorXd d = testing::RandomVector(fem.num_dofs(), 1.0, &rng);
  const double e = 1e-6;
  const Eigen::VectorXd fd = (fem.InternalForces(u + e * d) - fem.InternalForces(u - e * d)) / (2 * e);
  EXPECT_LT((K * d - fd).norm(), 1e-7 * fd.norm());
}

TEST(StVKFem, RigidRotationProducesNoForce) {
  const TetMesh mesh = MakeBeam(TetSplit::kSix, 4);
  const StVKFem fem(mesh, BeamMaterial());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd u(fem.num_dofs());
  for (int v = 0; v < mesh.num_vertices(); ++v) u.segment<3>(3 * v) = (R - Eigen::Matrix3d::Identity()) * mesh.vertices[v];
  const double scale = fem.InternalForces(0.1 * u).norm();  // a non-rigid displacement's force
  EXPECT_LT(fem.InternalForces(u).norm(), 1e-10 * scale);
  EXPECT_LT(fem.Energy(u), 1e-20 * fem.Energy(0.1 * u) + 1e-16);
}

TEST(StVKFem, ForceHessianIsTheSecondDerivativeOfForces) {
  const TetMesh mesh = MakeBeam(TetSplit::kSix, 4);
  const StVKFem fem(mesh, BeamMaterial());
  std::mt19937 rng(4);
  const Eigen::VectorXd a = testing::RandomVector(fem.num_dofs(), 1.0, &rng);
  const Eigen::VectorXd b = testing::RandomVector(fem.num_dofs(), 1.0, &rng);
  // d/dt [K(t a) b] at t = 0 by central differences of the tangent stiffness.
  const double e = 1e-5;
  const Eigen::VectorXd fd = (fem.TangentStiffness(e * a) * b - fem.TangentStiffness(-e * a) * b) / (2 * e);
  EXPECT_LT((fem.ForceHessianAtRest(a, b) - fd).norm(), 1e-7 * fd.norm());
}

TEST(StVKFem, MassMatricesConserveTotalMass) {
  const TetMesh mesh = MakeBeam();
  const StVKFem fem(mesh, BeamMaterial());
  const double total = BeamMaterial().density * mesh.Volume();
  for (MassKind kind : {MassKind::kLumped, MassKind::kConsistent}) {
    const SparseMatrixd M = fem.MassMatrix(kind);
    Eigen::VectorXd ex = Eigen::VectorXd::Zero(fem.num_dofs());
    for (int v = 0; v < mesh.num_vertices(); ++v) ex[3 * v] = 1;
    EXPECT_NEAR(ex.dot(M * ex), total, 1e-10 * total);
  }
}

TEST(StVKFem, BadMaterialIsRejectedWithItsName) {
  const TetMesh mesh = MakeBeam(TetSplit::kSix, 4);
  StVKMaterial m = BeamMaterial();
  m.poisson_ratio = 0.5;
  try {
    StVKFem fem(mesh, m, "beam.yaml");
    FAIL() << "nu = 0.5 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("beam.yaml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Poisson"), std::string::npos);
  }
  m = BeamMaterial();
  m.youngs_modulus = 0;
  EXPECT_THROW(StVKFem(mesh, m), Error);
  m = BeamMaterial();
  m.density = -1;
  EXPECT_THROW(StVKFem(mesh, m), Error);
}

}  // namespace
}  // namespace contactlab
