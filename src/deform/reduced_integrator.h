// Implicit time stepping of a reduced deformable model (Barbič & James 2008, sec. 4: "a fast
// time step of deformable dynamics" run at the end of each haptic cycle): implicit Newmark
// (average acceleration, beta = 1/4, gamma = 1/2) with Newton iterations and Rayleigh
// damping, in mass-orthonormal reduced coordinates (reduced mass matrix = identity).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>

#include "deform/reduced_forces.h"
#include "reduced/reduced_state.h"

namespace contactlab {

struct IntegratorOptions {
  double time_step = 1e-3;        // seconds (> 0)
  double mass_damping = 0;        // Rayleigh alpha, 1/s (>= 0): D = alpha I + beta A
  double stiffness_damping = 0;   // Rayleigh beta, s (>= 0), with the linear stiffness A
  int newton_iterations = 1;      // maximum Newton iterations per step (>= 1)
  double newton_tolerance = 0;    // stop when |dq| <= tolerance * (1 + |q|); 0: run all
  // Throws Error naming WHERE for a non-positive step, negative damping or no iteration.
  void Validate(const std::string& where) const;
};

class ReducedIntegrator {
 public:
  // FORCES must outlive the integrator. Throws Error (see IntegratorOptions::Validate).
  ReducedIntegrator(const ReducedInternalForces& forces, const IntegratorOptions& options);

  int r() const { return forces_->r(); }
  const IntegratorOptions& options() const { return options_; }
  const ReducedState& state() const { return state_; }
  const ReducedVector& acceleration() const { return accel_; }
  // Sets q and qdot (r entries each) and the matching acceleration under zero external
  // force. Throws Error when sizes differ from r.
  void SetState(const ReducedState& state);
  void Reset() { SetState(ReducedState(r())); }

  // Advances one step with reduced external force F_EXT (r entries, e.g. U^T f for point
  // forces). With K_EXT (r x r), the external force is taken as F_EXT - K_EXT (q' - q) at the
  // new state q' (linearly implicit, e.g. a penalty contact's stiffness), which keeps stiff
  // contact stable at the haptic rate. Returns the Newton iterations done. Allocates
  // nothing, throws nothing.
  int Step(const ReducedVector& f_ext, const ReducedMatrix* K_ext = nullptr);

  double KineticEnergy() const { return 0.5 * state_.qdot.squaredNorm(); }
  double PotentialEnergy();

 private:
  const ReducedInternalForces* forces_;
  IntegratorOptions options_;
  ReducedState state_;
  ReducedVector accel_;
  // Scratch, sized once.
  ReducedInternalForces::Workspace ws_;
  ReducedVector q1_, v1_, a1_, f_, residual_;
  ReducedMatrix K_, J_, damping_;
  Eigen::LLT<ReducedMatrix> llt_;
  bool constant_jacobian_ = false;  // linear model: J is factored once
  bool factor_has_external_ = false;  // the factor includes the last step's K_ext
};

// Static equilibrium f(q) = F_EXT by Newton's method with LOAD_STEPS equal load increments
// and up to ITERATIONS Newton steps per increment (backtracking on the residual norm).
// Returns q. Never throws; a non-converged solve returns the last iterate.
ReducedVector SolveReducedStatic(const ReducedInternalForces& forces, const ReducedVector& f_ext,
                                 int load_steps = 10, int iterations = 30);

}  // namespace contactlab
