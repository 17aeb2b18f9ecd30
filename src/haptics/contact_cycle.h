// The contact half of one cycle, the same sequence wherever a contact model runs cycle by cycle
// (Barbič & James 2008, sec. 3.4, 4 and 5): guard the model's temporal coherence against the
// moving body's speed, hold the deformations fixed for the query, restart a diverged one instead
// of querying it, evaluate, and at the end of the cycle step the deformations with the contact
// forces as external loads. The live haptic cycle (haptic_cycle.h, which the closed-loop study
// drives) and the offline experiment runner (experiment/studies/contact/run_job.cc) both run it.
// Allocation-free, exception-free and lock-free after construction.
#pragma once

#include <cstdint>

#include "contact/coherence_guard.h"
#include "contact/contact_model.h"
#include "deform/body_dynamics.h"
#include "geometry/pose.h"

namespace contactlab {

// What a cycle's query did beside its result.
struct ContactCycleQuery {
  double point_speed = 0;        // measured bound on the speed of the moving body's points, m/s
  bool coherence_reset = false;  // it moved faster than max_point_speed: the model was reset
  bool queried = false;          // false: a deformation was not finite; restarted, no query (faults = 1)
  std::int64_t query_ns = 0;     // the model's Evaluate, wall time (0 when not queried)
};

// What a cycle's deformation steps took, ns (0 for a rigid body).
struct ContactCycleSteps {
  std::int64_t step_A_ns = 0;
  std::int64_t step_B_ns = 0;
};

class ContactCycle {
 public:
  // MODEL (may be null: free space, then nothing is queried or stepped), the deformable bodies'
  // dynamics DYNAMICS_A and DYNAMICS_B (null: rigid) and the moving body's COHERENCE guard must
  // outlive the cycle.
  ContactCycle(ContactModel* model, BodyDynamics* dynamics_A, BodyDynamics* dynamics_B, CoherenceGuard* coherence)
      : model_(model), dynamics_A_(dynamics_A), dynamics_B_(dynamics_B), coherence_(coherence) {}

  // Starts over with the moving body at X_MOVING: the coherence guard from there (its resets
  // counted from 0) and the deformable bodies at rest. The model is not reset.
  void Start(const Pose& X_moving);

  // This cycle's query with the moving body at X_MOVING, whose poses, cycle and node budget
  // QUERY already holds: the coherence guard (a reset of the model's coherence when the body
  // moved too fast), the deformations prepared into QUERY (held fixed during it), a diverged
  // one restarted from rest instead of queried (no force, stats.faults = 1), else the model's
  // Evaluate. *INFO (when given) says what happened. Requires a model.
  ContactResult Evaluate(const Pose& X_moving, ContactQuery* query, ContactCycleQuery* info = nullptr);

  // The end of the cycle: steps the deformable bodies (A, then B) with the reduced contact
  // forces and stiffness the query wrote. Returns the time each step took.
  ContactCycleSteps StepDeformations();

  ContactModel* model() const { return model_; }
  BodyDynamics* dynamics_A() const { return dynamics_A_; }
  BodyDynamics* dynamics_B() const { return dynamics_B_; }
  bool deformable() const { return dynamics_A_ != nullptr || dynamics_B_ != nullptr; }

 private:
  ContactModel* model_;
  BodyDynamics* dynamics_A_;
  BodyDynamics* dynamics_B_;
  CoherenceGuard* coherence_;
};

}  // namespace contactlab
