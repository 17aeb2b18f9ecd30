// One deformable body's side of the two-way contact coupling (Barbič & James 2008, sec. 4 and
// 5): the contact query reads the body's reduced coordinates and writes its reduced contact force
// (and stiffness, for a linearly implicit step); after the query the body's integrator takes one
// step with them. Used by the haptic cycle and the experiment runner alike. Allocation-free.
#pragma once

#include "contact/contact_model.h"
#include "deform/reduced_integrator.h"

namespace contactlab {

class ReducedContactCoupling {
 public:
  enum class Body { kA, kB };

  ReducedContactCoupling() = default;  // inactive: a rigid body
  // INTEGRATOR (must outlive the coupling) steps body BODY of the queries. IMPLICIT_CONTACT:
  // the step also takes the contact's reduced stiffness; false applies the force alone.
  ReducedContactCoupling(ReducedIntegrator* integrator, bool implicit_contact, Body body)
      : integrator_(integrator), implicit_(implicit_contact), body_(body) {
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
  // Points query Q at the body's state and at the force (and stiffness) it is to fill.
  void Prepare(ContactQuery* q) {
    f_.setZero();
    const bool a = body_ == Body::kA;
    (a ? q->q_A : q->q_B) = &integrator_->state();
    (a ? q->reduced_force_A : q->reduced_force_B) = &f_;
    (a ? q->reduced_stiffness_A : q->reduced_stiffness_B) = implicit_ ? &K_ : nullptr;
  }
  // One step with the force of the query just made. STAGGERED: the other body deforms too and
  // steps separately, so the stiffness is scaled by ContactQuery::kStaggeredStiffnessFactor.
  void Step(bool staggered) {
    if (staggered) K_ *= ContactQuery::kStaggeredStiffnessFactor;
    integrator_->Step(f_, implicit_ ? &K_ : nullptr);
  }

 private:
  ReducedIntegrator* integrator_ = nullptr;
  bool implicit_ = true;
  Body body_ = Body::kA;
  ReducedVector f_;
  ReducedMatrix K_;
};

}  // namespace contactlab
