// The contact half of one cycle (haptics/contact_cycle.h).
#include "haptics/contact_cycle.h"

#include <chrono>

namespace contactlab {
namespace {

std::int64_t NanosecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void ContactCycle::Start(const Pose& X_moving) {
  coherence_->Start(X_moving);
  if (dynamics_A_ != nullptr) dynamics_A_->Reset();
  if (dynamics_B_ != nullptr) dynamics_B_->Reset();
}

ContactResult ContactCycle::Evaluate(const Pose& X_moving, ContactQuery* query, ContactCycleQuery* info) {
  ContactCycleQuery done;
  // Temporal-coherence guard: the moving body's motion since the previous query, as a bound on
  // the speed of its points, against the speed the model's coherence assumes. Faster: this
  // cycle traverses in full and coherence restarts from it.
  if (coherence_->Check(X_moving, &done.point_speed)) {
    model_->ResetCoherence();
    done.coherence_reset = true;
  }
  // The deformations, held fixed during the query; one a step left non-finite (diverged) is
  // restarted from rest and not queried.
  if (dynamics_A_ != nullptr) query->deformation_A = dynamics_A_->Prepare();
  if (dynamics_B_ != nullptr) query->deformation_B = dynamics_B_->Prepare();
  ContactResult result;
  if (RestartDiverged({dynamics_A_, dynamics_B_})) {
    const auto t0 = std::chrono::steady_clock::now();
    result = model_->Evaluate(*query);
    done.query_ns = NanosecondsSince(t0);
    done.queried = true;
  } else {
    result.stats.faults = 1;
  }
  if (info != nullptr) *info = done;
  return result;
}

ContactCycleSteps ContactCycle::StepDeformations() {
  ContactCycleSteps steps;
  if (dynamics_A_ != nullptr) {
    const auto t0 = std::chrono::steady_clock::now();
    dynamics_A_->Step();
    steps.step_A_ns = NanosecondsSince(t0);
  }
  if (dynamics_B_ != nullptr) {
    const auto t0 = std::chrono::steady_clock::now();
    dynamics_B_->Step();
    steps.step_B_ns = NanosecondsSince(t0);
  }
  return steps;
}

}  // namespace contactlab
