#include "deform/reduced_forces.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "deform/nonlinear_basis.h"
#include "beam_fixture.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BeamOptions;
using testing::MakeBeam;

// For random q the reduced polynomials equal the projected full StVK model.
void ExpectReducedForcesAreProjectedFullForces(const ReducedModel& model, double q_scale, int seed) {
  const StVKFem fem(model.mesh, model.material);
  const ReducedInternalForces& forces = model.forces;
  auto ws = forces.MakeWorkspace();
  std::mt19937 rng(seed);
  const Eigen::MatrixXd& U = model.basis;
  for (int trial = 0; trial < 5; ++trial) {
    const ReducedVector q = testing::RandomVector(model.r(), q_scale, &rng);
    ReducedVector f;
    f.resize(model.r());
    ReducedMatrix K(model.r(), model.r());
    forces.Evaluate(q, &f, &K, &ws);
    const Eigen::VectorXd u = U * Eigen::VectorXd(q);
    const Eigen::VectorXd f_ref = U.transpose() * fem.InternalForces(u);
    EXPECT_LT((Eigen::VectorXd(f) - f_ref).norm(), 1e-10 * f_ref.norm()) << "trial " << trial;
    const Eigen::MatrixXd K_ref = U.transpose() * fem.TangentStiffness(u) * U;
    EXPECT_LT((Eigen::MatrixXd(K) - K_ref).norm(), 1e-10 * K_ref.norm()) << "trial " << trial;
    const double w_ref = fem.Energy(u);
    EXPECT_NEAR(forces.Energy(q, &ws), w_ref, 1e-10 * w_ref);
    // Tangent stiffness against finite differences of the reduced force.
    const ReducedVector d = testing::RandomVector(model.r(), 1.0, &rng);
    const double e = 1e-6 * q_scale;
    ReducedVector fp(model.r()), fm(model.r());
    forces.Evaluate(q + e * d, &fp, nullptr, &ws);
    forces.Evaluate(q - e * d, &fm, nullptr, &ws);
    const Eigen::VectorXd fd = (fp - fm) / (2 * e);
    EXPECT_LT((Eigen::VectorXd(K * d) - fd).norm(), 1e-6 * fd.norm());
  }
}

TEST(ReducedForces, StVKPolynomialEqualsProjectedFullModelAnchored) {
  const ReducedModel model = BuildReducedModel(MakeBeam(), BeamOptions(12, ReducedModelKind::kStVK), "beam");
  EXPECT_LT((model.basis.transpose() * StVKFem(model.mesh, model.material).MassMatrix(MassKind::kLumped) * model.basis -
             Eigen::MatrixXd::Identity(12, 12)).cwiseAbs().maxCoeff(), 1e-10);
  // Large q: displacements of a sizeable fraction of the beam length, all terms matter.
  ExpectReducedForcesAreProjectedFullForces(model, 2.0, 11);
}

TEST(ReducedForces, StVKPolynomialEqualsProjectedFullModelFreeBody) {
  auto options = BeamOptions(8, ReducedModelKind::kStVK);
  options.anchoring = Anchoring::Free();
  options.mass = MassKind::kConsistent;
  const ReducedModel model = BuildReducedModel(MakeBeam(TetSplit::kFive, 8), options, "free beam");
  ExpectReducedForcesAreProjectedFullForces(model, 2.0, 12);
}

TEST(ReducedForces, LinearModelIsTheProjectedLinearStiffness) {
  const ReducedModel model = BuildReducedModel(MakeBeam(), BeamOptions(6, ReducedModelKind::kLinear), "beam");
  const StVKFem fem(model.mesh, model.material);
  const Eigen::MatrixXd A = model.basis.transpose() * fem.LinearStiffness() * model.basis;
  EXPECT_LT((model.forces.linear() - A).norm(), 1e-10 * A.norm());
  // Linear modes: the reduced stiffness is diagonal with the eigenvalues.
  EXPECT_LT((A - Eigen::MatrixXd(model.eigenvalues.asDiagonal())).norm(), 1e-8 * A.norm());
  auto ws = model.forces.MakeWorkspace();
  std::mt19937 rng(5);
  const ReducedVector q = testing::RandomVector(6, 1.0, &rng);
  ReducedVector f(6);
  model.forces.Evaluate(q, &f, nullptr, &ws);
  EXPECT_LT((Eigen::VectorXd(f) - A * Eigen::VectorXd(q)).norm(), 1e-12 * f.norm());
}

TEST(ReducedForces, InconsistentCoefficientSizesAreRejected) {
  EXPECT_THROW(ReducedInternalForces(ReducedModelKind::kStVK, Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Zero(6, 2),
                                     Eigen::MatrixXd::Zero(6, 6)),
               Error);
  EXPECT_THROW(ReducedInternalForces(ReducedModelKind::kLinear, Eigen::MatrixXd::Identity(kMaxReducedModes + 1, kMaxReducedModes + 1),
                                     {}, {}),
               Error);
}

}  // namespace
}  // namespace contactlab
