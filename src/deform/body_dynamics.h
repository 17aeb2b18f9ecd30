// One deformable body's dynamics under contact (Barbič & James 2008, sec. 4 and 5): its reduced
// model, the integrator that steps it at the haptic cycle, how the contact enters the step
// (coupling mode) and whether the other body steps separately (staggering). Each cycle the
// contact query reads the body's reduced coordinates and writes its reduced contact force (and
// stiffness, for a linearly implicit step) through the BodyDeformation that Prepare hands out;
// after the query Step advances the body with them. The offline runner, the live session and
// the closed-loop study all step their deformable bodies through it (built from a scene body by
// MakeBodyDynamics, scene/scene_assets.h). Allocation-free after construction.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>

#include "deform/reduced_integrator.h"
#include "deform/reduced_model.h"
#include "reduced/reduced_state.h"

namespace contactlab {

class BodyDynamics {
 public:
  // When both bodies deform and each integrator steps on its own with the other held fixed
  // (staggered), the gap closes from both sides while each linearly implicit step sees only
  // its own side: each integrator takes kStaggeredStiffnessFactor times its stiffness, exact for
  // equal compliances and overdamped otherwise (without it two pressed bodies oscillate).
  static constexpr double kStaggeredStiffnessFactor = 2.0;

  // MODEL (kept) steps with OPTIONS (time step = the haptic cycle) by an integrator this object
  // owns. IMPLICIT_CONTACT: the step also takes the contact's reduced stiffness; false applies
  // the force alone (the paper's explicit order). STAGGERED: the other body of the contact
  // deforms too and steps separately. Throws Error for invalid options (IntegratorOptions).
  BodyDynamics(std::shared_ptr<const ReducedModel> model, const IntegratorOptions& options, bool implicit_contact,
               bool staggered)
      : model_(std::move(model)),
        integrator_(std::make_unique<ReducedIntegrator>(model_->forces, options)),
        implicit_(implicit_contact),
        staggered_(staggered) {
    u_.setZero(model_->basis.rows());
    // |U_v q| <= ||U_v||_F ||q|| for each vertex's 3 x r block U_v of the basis.
    for (Eigen::Index v = 0; v + 2 < model_->basis.rows(); v += 3) {
      displacement_per_q_ = std::max(displacement_per_q_, model_->basis.middleRows(v, 3).norm());
    }
    ZeroForce();
  }
  BodyDynamics(const BodyDynamics&) = delete;
  BodyDynamics& operator=(const BodyDynamics&) = delete;

  int r() const { return integrator_->r(); }
  const ReducedIntegrator& integrator() const { return *integrator_; }
  const ReducedState& state() const { return integrator_->state(); }
  bool implicit_contact() const { return implicit_; }
  bool staggered() const { return staggered_; }

  // Back to rest, no force.
  void Reset() {
    integrator_->Reset();
    ZeroForce();
  }
  // Puts the body in STATE (r entries each; throws Error otherwise), no force.
  void SetState(const ReducedState& state) {
    integrator_->SetState(state);
    ZeroForce();
  }
  // False when a step has left the state non-finite (a diverged integration): a contact query
  // must not read it (see RestartDiverged).
  bool finite() const { return state().q.allFinite() && state().qdot.allFinite(); }
  // This cycle's deformation for the contact query: the body's state in, its reduced force (and
  // stiffness) out, zeroed now. Valid until the next Prepare or Step.
  const BodyDeformation* Prepare() {
    f_.setZero();
    if (implicit_) K_.setZero();
    deformation_ = {&integrator_->state(), &f_, implicit_ ? &K_ : nullptr};
    return &deformation_;
  }
  // One step with the force (and stiffness) of the query just made; staggered (as constructed):
  // with kStaggeredStiffnessFactor times the stiffness.
  void Step() {
    if (staggered_) K_ *= kStaggeredStiffnessFactor;
    integrator_->Step(f_, implicit_ ? &K_ : nullptr);
  }

  // Elastic and kinetic energy of the current state, J (mass-normalised coordinates).
  double PotentialEnergy() { return integrator_->PotentialEnergy(); }
  double KineticEnergy() const { return integrator_->KineticEnergy(); }
  // An upper bound on MaxDisplacement() from ||q|| alone (no pass over the mesh).
  double MaxDisplacementBound() const { return displacement_per_q_ * integrator_->state().q.norm(); }
  // Largest displacement |U_v q| of a simulation-mesh vertex at the current state, metres.
  double MaxDisplacement() {
    u_.noalias() = model_->basis * integrator_->state().q;
    double max2 = 0;
    for (Eigen::Index v = 0; v + 2 < u_.size(); v += 3) max2 = std::max(max2, u_.segment<3>(v).squaredNorm());
    return std::sqrt(max2);
  }

 private:
  void ZeroForce() {
    f_.setZero(integrator_->r());
    K_.setZero(integrator_->r(), integrator_->r());
  }

  std::shared_ptr<const ReducedModel> model_;
  std::unique_ptr<ReducedIntegrator> integrator_;
  bool implicit_;
  bool staggered_;
  ReducedVector f_;
  ReducedMatrix K_;
  Eigen::VectorXd u_;  // 3#V scratch: U q
  double displacement_per_q_ = 0;  // max over vertices of ||U_v||_F
  BodyDeformation deformation_;
};

// Restarts from rest each of BODIES (null ones skipped) whose state a step has left non-finite;
// false when any had: this cycle's contact query must not be made (no force, a counted contact
// fault), and the following cycles go on from rest. Allocation-free, throws nothing.
inline bool RestartDiverged(std::initializer_list<BodyDynamics*> bodies) {
  bool finite = true;
  for (BodyDynamics* d : bodies) {
    if (d != nullptr && !d->finite()) {
      d->Reset();
      finite = false;
    }
  }
  return finite;
}

}  // namespace contactlab
