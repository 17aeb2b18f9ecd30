// The per-cycle operations (time step, reduced forces, embedded point queries) allocate
// nothing: malloc, calloc, realloc and operator new are counted (tests/allocation_counter.h).
#include <gtest/gtest.h>

#include <cstddef>

#include "allocation_counter.h"
#include "deform/deformed_distance_field.h"
#include "deform/embedded_points.h"
#include "deform/reduced_integrator.h"
#include "beam_fixture.h"
#include "sdf/distance_field.h"

namespace contactlab {
namespace {

TEST(NoAllocation, CounterSeesAllocations) {
  const long before = testing::AllocationCount();
  Eigen::VectorXd* v = new Eigen::VectorXd(100);
  const long allocations = testing::AllocationCount() - before;
  delete v;
  EXPECT_GE(allocations, 2);
}

TEST(NoAllocation, TimeStepForcesAndPointQueriesAllocateNothing) {
  for (auto kind : {ReducedModelKind::kStVK, ReducedModelKind::kLinear}) {
    const ReducedModel model = BuildReducedModel(testing::MakeBeam(), testing::BeamOptions(20, kind), "beam");
    IntegratorOptions options;
    options.time_step = 1e-3;
    options.mass_damping = 0.5;
    options.stiffness_damping = 1e-3;
    options.newton_iterations = 3;
    options.newton_tolerance = 1e-12;
    ReducedIntegrator integrator(model.forces, options);
    const std::vector<Eigen::Vector3d> points = {{1.0, 0.125, 0.125}, {0.5, 0.25, 0.1}};
    const std::vector<Eigen::Vector3d> normals = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
    const EmbeddedPoints embedded(model.mesh, model.basis, points, normals);
    auto ws = model.forces.MakeWorkspace();
    ReducedVector f_ext = ReducedVector::Zero(20), f(20);
    ReducedMatrix K(20, 20);
    // A contact stiffness (symmetric positive semidefinite), given on every other step.
    ReducedMatrix K_contact = ReducedMatrix::Zero(20, 20);
    K_contact(0, 0) = K_contact(1, 1) = 50;
    K_contact(0, 1) = K_contact(1, 0) = 10;
    double sink = 0;

    const long before = testing::AllocationCount();
    for (int step = 0; step < 20; ++step) {
      f_ext.setZero();
      embedded.AddPointForce(0, Eigen::Vector3d(0, -100, 0), f_ext.data());
      integrator.Step(f_ext, step % 2 == 0 ? &K_contact : nullptr);
      const double* q = integrator.state().q.data();
      sink += embedded.Position(0, q).y() + embedded.Normal(1, q).x() + embedded.DeformationGradient(1, q)(0, 0);
      model.forces.Evaluate(integrator.state().q, &f, &K, &ws);
      sink += f[0] + K(0, 0) + model.forces.Energy(integrator.state().q, &ws);
    }
    const long allocations = testing::AllocationCount() - before;
    EXPECT_EQ(allocations, 0) << (kind == ReducedModelKind::kStVK ? "reduced StVK" : "linear");
    EXPECT_TRUE(std::isfinite(sink));
    EXPECT_LT(integrator.state().q.norm(), 1e3);
  }
}

TEST(NoAllocation, DeformedFieldUpdateAndQueriesAllocateNothing) {
  const ReducedModel model = BuildReducedModel(testing::MakeBeam(), testing::BeamOptions(15, ReducedModelKind::kLinear), "beam");
  // The rest field of the beam [0, 1] x [0, 0.25]^2 (box distance, exact enough inside), 5 cm grid.
  const double h = 0.05;
  const Eigen::Vector3i dims(27, 14, 14);
  const Eigen::Vector3d origin(-0.15, -0.2, -0.2);
  std::vector<float> values;
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) {
        const Eigen::Vector3d p = origin + h * Eigen::Vector3d(i, j, k);
        const Eigen::Vector3d q = (p - Eigen::Vector3d(0.5, 0.125, 0.125)).cwiseAbs() - Eigen::Vector3d(0.5, 0.125, 0.125);
        values.push_back(float(q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0)));
      }
  const auto rest = std::make_shared<const DistanceField>(origin, h, dims, values);
  for (int domains : {1, 3}) {
    DeformedFieldOptions o;
    o.domains = domains;
    const DeformedDistanceField field(rest, model.mesh, model.basis, o, "beam");
    DeformedFieldState state(field);
    ReducedVector q = ReducedVector::Zero(15);
    double sink = 0;
    const long before = testing::AllocationCount();
    for (int step = 0; step < 20; ++step) {
      q[step % 15] += 0.001;
      state.Update(field, q.data());
      for (int i = 0; i < 50; ++i) {
        const float x[3] = {0.02f * float(i), 0.26f, 0.1f};
        int nearest = -1;
        sink += field.Distance(state, x, &nearest) + nearest;
      }
    }
    EXPECT_EQ(testing::AllocationCount() - before, 0) << domains << " domains";
    EXPECT_TRUE(std::isfinite(sink));
  }
}

}  // namespace
}  // namespace contactlab
