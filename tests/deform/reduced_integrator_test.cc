#include "deform/reduced_integrator.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "deform/embedded_points.h"
#include "deform/modal_analysis.h"
#include "beam_fixture.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BeamOptions;
using testing::MakeBeam;

TEST(ReducedIntegrator, UndampedNewmarkConservesEnergy) {
  const ReducedModel model = BuildReducedModel(MakeBeam(), BeamOptions(10, ReducedModelKind::kStVK), "beam");
  IntegratorOptions options;
  const double period = 2 * M_PI / std::sqrt(model.eigenvalues[0]);
  options.time_step = period / 2000;
  options.newton_iterations = 20;
  options.newton_tolerance = 1e-13;
  ReducedIntegrator integrator(model.forces, options);
  ReducedState s(model.r());
  s.q[0] = 0.5;  // a first-mode-like amplitude where nonlinear terms are active
  s.q[2] = -0.2;
  integrator.SetState(s);
  const double e0 = integrator.KineticEnergy() + integrator.PotentialEnergy();
  double max_drift = 0;
  const ReducedVector zero = ReducedVector::Zero(model.r());
  for (int step = 0; step < 8000; ++step) {  // four periods of the lowest linear mode
    integrator.Step(zero);
    const double e = integrator.KineticEnergy() + integrator.PotentialEnergy();
    max_drift = std::max(max_drift, std::abs(e - e0) / e0);
  }
  // Average-acceleration Newmark conserves energy exactly for linear forces; for StVK the
  // error is O(h^2) and oscillates.
  EXPECT_LT(max_drift, 0.005);
  std::printf("energy drift over 8000 steps: %.2e\n", max_drift);
  // The motion was not trivial: the state moved away from the initial one.
  EXPECT_GT(integrator.KineticEnergy(), 0);
}

// A step with the contact stiffness K solves the equation of motion with the external force
// linearised about the step's start, a1 + f(q1) + D v1 = f_ext - K (q1 - q0), exactly for the
// linear model (one Newton iteration suffices); a step without K after it solves the plain
// equation again (the linear model's constant factor is restored).
TEST(ReducedIntegrator, ContactStiffnessEntersTheStepImplicitlyAndLeavesWithIt) {
  for (auto kind : {ReducedModelKind::kLinear, ReducedModelKind::kStVK}) {
    const ReducedModel model = BuildReducedModel(MakeBeam(), BeamOptions(6, kind), "beam");
    IntegratorOptions options;
    options.time_step = 1e-3;
    options.mass_damping = 0.5;
    options.stiffness_damping = 1e-3;
    options.newton_iterations = kind == ReducedModelKind::kLinear ? 1 : 30;
    options.newton_tolerance = kind == ReducedModelKind::kLinear ? 0 : 1e-14;
    ReducedIntegrator integrator(model.forces, options);
    const Eigen::MatrixXd D = 0.5 * Eigen::MatrixXd::Identity(6, 6) + 1e-3 * model.forces.linear();
    ReducedMatrix K = ReducedMatrix::Zero(6, 6);
    for (int j = 0; j < 6; ++j) K(j, j) = 1e3 * (j + 1);
    K(0, 1) = K(1, 0) = 200;
    ReducedVector f_ext(6);
    f_ext << 3, -1, 0.5, 0, 2, -0.7;
    auto ws = model.forces.MakeWorkspace();
    ReducedVector f_int(6);
    for (int step = 0; step < 6; ++step) {
      const bool with_k = step % 2 == 0;
      const ReducedVector q0 = integrator.state().q;
      integrator.Step(f_ext, with_k ? &K : nullptr);
      const ReducedState& s = integrator.state();
      model.forces.Evaluate(s.q, &f_int, nullptr, &ws);
      Eigen::VectorXd residual = integrator.acceleration() + f_int + D * Eigen::VectorXd(s.qdot) - f_ext;
      if (with_k) residual += K * (s.q - q0);
      EXPECT_LT(residual.norm(), 1e-8 * f_ext.norm()) << "step " << step << (with_k ? " with K" : " without K");
    }
    // The stiffness matters: the same force with a K comparable to the step's inertia term
    // (4 / h^2) moves the body less.
    const ReducedMatrix stiff = 1e7 * ReducedMatrix::Identity(6, 6);
    ReducedIntegrator a(model.forces, options), b(model.forces, options);
    a.Step(f_ext);
    b.Step(f_ext, &stiff);
    EXPECT_LT(b.state().q.norm(), 0.9 * a.state().q.norm());
  }
}

TEST(ReducedIntegrator, DampingDissipatesEnergy) {
  const ReducedModel model = BuildReducedModel(MakeBeam(), BeamOptions(6, ReducedModelKind::kLinear), "beam");
  IntegratorOptions options;
  options.time_step = 1e-3;
  options.mass_damping = 1.0;
  options.stiffness_damping = 1e-3;
  ReducedIntegrator integrator(model.forces, options);
  ReducedState s(6);
  s.q[0] = 0.2;
  integrator.SetState(s);
  const double e0 = integrator.PotentialEnergy();
  for (int i = 0; i < 2000; ++i) integrator.Step(ReducedVector::Zero(6));
  EXPECT_LT(integrator.KineticEnergy() + integrator.PotentialEnergy(), 0.5 * e0);
}

TEST(ReducedIntegrator, LinearStaticDeflectionConvergesToFullFemAsRGrows) {
  const TetMesh mesh = MakeBeam();
  const StVKMaterial material = testing::BeamMaterial();
  const StVKFem fem(mesh, material);
  const auto fixed = FindFixedVertices(mesh, testing::BeamAnchoring());
  // Full linear FEM under a downward tip load spread over the end face x = 1.
  const std::vector<int> free = FreeDofs(fixed);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(fem.num_dofs());
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices[v].x() > 1 - 1e-9) f[3 * v + 1] = -1.0;
  Eigen::VectorXd ff(free.size());
  for (std::size_t k = 0; k < free.size(); ++k) ff[k] = f[free[k]];
  Eigen::SimplicialLDLT<SparseMatrixd> ldlt(RestrictToDofs(fem.LinearStiffness(), free));
  const Eigen::VectorXd uf = ldlt.solve(ff);
  Eigen::VectorXd u_full = Eigen::VectorXd::Zero(fem.num_dofs());
  for (std::size_t k = 0; k < free.size(); ++k) u_full[free[k]] = uf[k];

  double previous = 1e300, first = 0;
  for (int r : {1, 2, 4, 8, 16, 32}) {
    const ReducedModel model = BuildReducedModel(mesh, BeamOptions(r, ReducedModelKind::kLinear), "beam");
    const ReducedVector fq = model.basis.transpose() * f;
    const ReducedVector q = SolveReducedStatic(model.forces, fq, 1, 2);
    const double err = (model.basis * Eigen::VectorXd(q) - u_full).norm() / u_full.norm();
    if (r == 1) first = err;
    EXPECT_LE(err, previous * 1.001) << "r = " << r;
    previous = err;
  }
  EXPECT_LT(previous, 0.05);
  EXPECT_LT(previous, 0.5 * first);
}

TEST(ReducedIntegrator, LargeRotationInflatesLinearModelButNotReducedStVK) {
  const TetMesh mesh = MakeBeam();
  const double v0 = mesh.Volume();
  const ReducedModel linear = BuildReducedModel(mesh, BeamOptions(10, ReducedModelKind::kLinear), "beam");
  const ReducedModel stvk = BuildReducedModel(mesh, BeamOptions(15, ReducedModelKind::kStVK), "beam");
  // Tip load at the centre of the free end, sized so the linear model deflects 0.6 L.
  const std::vector<Eigen::Vector3d> tip = {Eigen::Vector3d(1.0, 0.125, 0.125)};
  const EmbeddedPoints tip_linear(mesh, linear.basis, tip), tip_stvk(mesh, stvk.basis, tip);
  ReducedVector f_lin = ReducedVector::Zero(linear.r()), f_stvk = ReducedVector::Zero(stvk.r());
  tip_linear.AddPointForce(0, -Eigen::Vector3d::UnitY(), f_lin.data());
  const double unit_deflection = -tip_linear.Displacement(0, SolveReducedStatic(linear.forces, f_lin, 1, 2).data()).y();
  const double load = 0.6 / unit_deflection;
  f_lin *= load;
  tip_stvk.AddPointForce(0, -load * Eigen::Vector3d::UnitY(), f_stvk.data());

  const ReducedVector q_lin = SolveReducedStatic(linear.forces, f_lin, 1, 2);
  const ReducedVector q_stvk = SolveReducedStatic(stvk.forces, f_stvk, 20, 30);
  const double dv_lin = mesh.DeformedVolume(linear.basis * Eigen::VectorXd(q_lin)) / v0 - 1;
  const double dv_stvk = mesh.DeformedVolume(stvk.basis * Eigen::VectorXd(q_stvk)) / v0 - 1;
  // Static equilibrium was reached.
  auto ws = stvk.forces.MakeWorkspace();
  ReducedVector f_int(stvk.r());
  stvk.forces.Evaluate(q_stvk, &f_int, nullptr, &ws);
  EXPECT_LT((f_int - f_stvk).norm(), 1e-8 * f_stvk.norm());
  const Eigen::Vector3d tip_displacement = tip_stvk.Displacement(0, q_stvk.data());
  EXPECT_GT(-tip_displacement.y(), 0.2);  // a large deflection
  EXPECT_LT(tip_displacement.x(), -0.02);  // that shortens the beam: a rotation, not a shear
  EXPECT_GT(dv_lin, 0.10);
  EXPECT_LT(std::abs(dv_stvk), 0.25 * dv_lin);
  RecordProperty("volume_change_linear", std::to_string(dv_lin));
  RecordProperty("volume_change_stvk", std::to_string(dv_stvk));
  std::printf("volume change: linear %.4f, reduced StVK %.4f; StVK tip (%.3f, %.3f, %.3f)\n", dv_lin, dv_stvk,
              tip_displacement.x(), tip_displacement.y(), tip_displacement.z());
}

TEST(ReducedIntegrator, BadOptionsAreRejected) {
  const ReducedModel model = BuildReducedModel(MakeBeam(), BeamOptions(3, ReducedModelKind::kLinear), "beam");
  IntegratorOptions options;
  options.time_step = 0;
  EXPECT_THROW(ReducedIntegrator(model.forces, options), Error);
  options.time_step = 1e-3;
  options.newton_iterations = 0;
  EXPECT_THROW(ReducedIntegrator(model.forces, options), Error);
  options.newton_iterations = 1;
  ReducedIntegrator integrator(model.forces, options);
  EXPECT_THROW(integrator.SetState(ReducedState(4)), Error);
}

}  // namespace
}  // namespace contactlab
