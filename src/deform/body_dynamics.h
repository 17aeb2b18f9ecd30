// One deformable body's side of the two-way contact coupling (Barbič & James 2008, sec. 4 and
// 5): each cycle the contact query reads the body's reduced coordinates and writes its reduced
// contact force (and stiffness, for a linearly implicit step) through the BodyDeformation that
// Prepare hands out; after the query the body's integrator takes one step with them. The
// offline runner and the haptic cycle (of a live session, and of the closed-loop study) step
// their deformable bodies through it. Allocation-free.
#pragma once

#include "deform/reduced_integrator.h"
#include "reduced/reduced_state.h"

namespace contactlab {

class BodyDynamics {
 public:
  // When both bodies deform and each integrator steps on its own with the other held fixed
  // (staggered), the gap closes from both sides while each linearly implicit step sees only
  // its own side: each integrator takes kStaggeredStiffnessFactor times its stiffness, exact for
  // equal compliances and overdamped otherwise (without it two pressed bodies oscillate).
  static constexpr double kStaggeredStiffnessFactor = 2.0;

  BodyDynamics() = default;  // inactive: a rigid body
  // INTEGRATOR (must outlive this) steps the body. IMPLICIT_CONTACT: the step also takes the
  // contact's reduced stiffness; false applies the force alone.
  BodyDynamics(ReducedIntegrator* integrator, bool implicit_contact)
      : integrator_(integrator), implicit_(implicit_contact) {
    f_.setZero(integrator->r());
    K_.setZero(integrator->r(), integrator->r());
  }

  bool active() const { return integrator_ != nullptr; }
  const ReducedIntegrator& integrator() const { return *integrator_; }

  // Back to rest, no force.
  void Reset() {
    integrator_->Reset();
    f_.setZero();
    K_.setZero();
  }
  // This cycle's deformation for the contact query: the body's state in, its reduced force (and
  // stiffness) out, zeroed now. Valid until the next Prepare or Step.
  const BodyDeformation* Prepare() {
    f_.setZero();
    deformation_ = {&integrator_->state(), &f_, implicit_ ? &K_ : nullptr};
    return &deformation_;
  }
  // One step with the force of the query just made. STAGGERED: the other body deforms too and
  // steps separately (kStaggeredStiffnessFactor).
  void Step(bool staggered) {
    if (staggered) K_ *= kStaggeredStiffnessFactor;
    integrator_->Step(f_, implicit_ ? &K_ : nullptr);
  }

 private:
  ReducedIntegrator* integrator_ = nullptr;
  bool implicit_ = true;
  ReducedVector f_;
  ReducedMatrix K_;
  BodyDeformation deformation_;
};

}  // namespace contactlab
