// Implicit Newmark for reduced StVK (Barbič & James 2005, sec. 5; 2008, sec. 4).
#include "deform/reduced_integrator.h"

#include <cmath>

#include "util/error.h"

namespace contactlab {

void IntegratorOptions::Validate(const std::string& where) const {
  if (!(time_step > 0) || !std::isfinite(time_step)) Fail(where, "the time step must be positive");
  if (!(mass_damping >= 0) || !(stiffness_damping >= 0)) Fail(where, "Rayleigh damping coefficients must be >= 0");
  if (newton_iterations < 1) Fail(where, "at least one Newton iteration per step is needed");
  if (!(newton_tolerance >= 0)) Fail(where, "the Newton tolerance must be >= 0");
}

ReducedIntegrator::ReducedIntegrator(const ReducedInternalForces& forces, const IntegratorOptions& options)
    : forces_(&forces), options_(options), ws_(forces.MakeWorkspace()) {
  options.Validate("integrator");
  const int n = forces.r();
  q1_.setZero(n);
  v1_.setZero(n);
  a1_.setZero(n);
  f_.setZero(n);
  residual_.setZero(n);
  K_.setZero(n, n);
  J_.setZero(n, n);
  damping_ = options.mass_damping * ReducedMatrix::Identity(n, n) + options.stiffness_damping * forces.linear();
  constant_jacobian_ = forces.kind() == ReducedModelKind::kLinear;
  const double h = options.time_step;
  if (constant_jacobian_) {
    J_ = (4 / (h * h)) * ReducedMatrix::Identity(n, n) + (2 / h) * damping_ + forces.linear();
    llt_.compute(J_);
  } else {
    llt_.compute(ReducedMatrix::Identity(n, n));  // sizes the factor's storage
  }
  Reset();
}

void ReducedIntegrator::SetState(const ReducedState& state) {
  if (state.q.size() != r() || state.qdot.size() != r()) {
    Fail("integrator", "the state has " + std::to_string(state.q.size()) + " coordinates, the model " + std::to_string(r()));
  }
  state_ = state;
  forces_->Evaluate(state_.q, &f_, nullptr, &ws_);
  accel_ = -f_ - damping_ * state_.qdot;
}

int ReducedIntegrator::Step(const ReducedVector& f_ext, const ReducedMatrix* K_ext) {
  const double h = options_.time_step;
  const ReducedVector& q = state_.q;
  const ReducedVector& v = state_.qdot;
  // Predictor: constant velocity.
  q1_ = q + h * v;
  int it = 0;
  for (; it < options_.newton_iterations; ++it) {
    a1_ = (4 / (h * h)) * (q1_ - q - h * v) - accel_;
    v1_ = (2 / h) * (q1_ - q) - v;
    if (constant_jacobian_ && K_ext == nullptr) {
      forces_->Evaluate(q1_, &f_, nullptr, &ws_);
      if (factor_has_external_) {  // back to the constant factor
        J_ = forces_->linear() + (2 / h) * damping_;
        J_.diagonal().array() += 4 / (h * h);
        llt_.compute(J_);
        factor_has_external_ = false;
      }
    } else {
      factor_has_external_ = K_ext != nullptr;
      forces_->Evaluate(q1_, &f_, constant_jacobian_ ? nullptr : &K_, &ws_);
      if (constant_jacobian_) {
        J_ = forces_->linear() + (2 / h) * damping_;
      } else {
        J_ = K_ + (2 / h) * damping_;
      }
      J_.diagonal().array() += 4 / (h * h);
      if (K_ext != nullptr) J_ += *K_ext;
      llt_.compute(J_);
    }
    residual_ = a1_ + f_ - f_ext;
    residual_.noalias() += damping_ * v1_;
    if (K_ext != nullptr) residual_.noalias() += *K_ext * (q1_ - q);
    llt_.solveInPlace(residual_);
    q1_ -= residual_;
    if (options_.newton_tolerance > 0 && residual_.norm() <= options_.newton_tolerance * (1 + q1_.norm())) {
      ++it;
      break;
    }
  }
  // Newmark update with the final iterate.
  a1_ = (4 / (h * h)) * (q1_ - q - h * v) - accel_;
  v1_ = (2 / h) * (q1_ - q) - v;
  state_.q = q1_;
  state_.qdot = v1_;
  accel_ = a1_;
  return it;
}

double ReducedIntegrator::PotentialEnergy() { return forces_->Energy(state_.q, &ws_); }

ReducedVector SolveReducedStatic(const ReducedInternalForces& forces, const ReducedVector& f_ext, int load_steps,
                                 int iterations) {
  const int n = forces.r();
  auto ws = forces.MakeWorkspace();
  ReducedVector q = ReducedVector::Zero(n), f(n), res(n), dq(n), trial(n);
  ReducedMatrix K(n, n);
  Eigen::LDLT<ReducedMatrix> ldlt(n);
  load_steps = std::max(1, load_steps);
  for (int s = 1; s <= load_steps; ++s) {
    const ReducedVector target = f_ext * (double(s) / load_steps);
    for (int it = 0; it < iterations; ++it) {
      forces.Evaluate(q, &f, &K, &ws);
      res = f - target;
      const double r0 = res.norm();
      if (r0 <= 1e-12 * (1 + target.norm())) break;
      ldlt.compute(K);
      dq = ldlt.solve(res);
      // Backtrack until the residual decreases.
      double step = 1;
      for (int b = 0; b < 20; ++b, step *= 0.5) {
        trial = q - step * dq;
        forces.Evaluate(trial, &f, nullptr, &ws);
        if ((f - target).norm() < r0) break;
      }
      q = trial;
    }
  }
  return q;
}

}  // namespace contactlab
