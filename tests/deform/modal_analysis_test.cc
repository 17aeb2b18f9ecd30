#include "deform/modal_analysis.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "deform/anchoring.h"
#include "beam_fixture.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BeamMaterial;
using testing::MakeBeam;

TEST(ModalAnalysis, AnchoredModesAreMassOrthonormalEigenpairs) {
  const TetMesh mesh = MakeBeam();
  const StVKFem fem(mesh, BeamMaterial());
  const SparseMatrixd M = fem.MassMatrix(MassKind::kConsistent);
  const SparseMatrixd K = fem.LinearStiffness();
  const auto fixed = FindFixedVertices(mesh, testing::BeamAnchoring());
  const LinearModes modes = ComputeLinearModes(K, M, fixed, 8);
  const Eigen::MatrixXd& U = modes.shapes;
  EXPECT_LT((U.transpose() * M * U - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT(modes.max_relative_residual, 1e-8);
  for (int i = 0; i < 8; ++i) {
    // Residual on all DOFs (fixed rows excluded: reaction forces live there).
    Eigen::VectorXd res = K * U.col(i) - modes.eigenvalues[i] * (M * U.col(i));
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (fixed[v]) res.segment<3>(3 * v).setZero();
    EXPECT_LT(res.norm(), 1e-8 * modes.eigenvalues[i] * (M * U.col(i)).norm());
    if (i > 0) {
      EXPECT_GE(modes.eigenvalues[i], modes.eigenvalues[i - 1]);
    }
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (fixed[v]) {
        EXPECT_EQ((U.block<3, 1>(3 * v, i).norm()), 0.0);
      }
  }
  // The two lowest modes of a square cantilever are the two bending directions (close; the
  // tet split is not symmetric, so not equal).
  EXPECT_NEAR(modes.eigenvalues[0], modes.eigenvalues[1], 0.3 * modes.eigenvalues[0]);
  // Euler-Bernoulli: omega_1 = 1.875^2 sqrt(E I / (rho A L^4)); a coarse linear-tet mesh is stiffer.
  const double a = 0.25, I = a * a * a * a / 12, A = a * a;
  const double omega = 1.875104 * 1.875104 * std::sqrt(BeamMaterial().youngs_modulus * I / (BeamMaterial().density * A));
  EXPECT_GT(std::sqrt(modes.eigenvalues[0]), 0.9 * omega);
  EXPECT_LT(std::sqrt(modes.eigenvalues[0]), 2.0 * omega);
}

TEST(ModalAnalysis, FreeBodyDropsRigidModes) {
  const TetMesh mesh = MakeBeam(TetSplit::kSix, 8);
  const StVKFem fem(mesh, BeamMaterial());
  const SparseMatrixd M = fem.MassMatrix(MassKind::kLumped);
  const SparseMatrixd K = fem.LinearStiffness();
  const std::vector<std::uint8_t> none(mesh.num_vertices(), 0);
  const LinearModes modes = ComputeLinearModes(K, M, none, 4);
  const Eigen::MatrixXd R = RigidModes(mesh, M);
  EXPECT_LT((K * R).norm(), 1e-8 * Eigen::MatrixXd(K).norm());
  EXPECT_LT((R.transpose() * M * modes.shapes).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_GT(modes.eigenvalues[0], 1e-3 * modes.eigenvalues[3]);
  EXPECT_LT(modes.max_relative_residual, 1e-8);
}

TEST(ModalAnalysis, TooManyModesForTheMeshIsAnError) {
  const TetMesh mesh = MakeBoxTetMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1, 1, 1);
  const StVKFem fem(mesh, BeamMaterial());
  const std::vector<std::uint8_t> none(mesh.num_vertices(), 0);
  EXPECT_THROW(ComputeLinearModes(fem.LinearStiffness(), fem.MassMatrix(MassKind::kLumped), none, 20), Error);
}

}  // namespace
}  // namespace contactlab
