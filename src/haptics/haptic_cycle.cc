// One haptic cycle (Barbič & James 2008, sec. 5).
#include "haptics/haptic_cycle.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace contactlab {

HapticCycle::HapticCycle(HapticDevice& device, ContactModel* model, const HapticCycleConfig& config)
    : device_(device),
      model_(model),
      config_(config),
      coupling_(config.alpha_per_cycle ? config.coupling : CouplingAtRate(config.coupling, config.cycle_seconds)),
      safety_(ResolveSafetyLimits(config.safety, device.capabilities())),
      coherence_(config.max_point_speed, config.cycle_seconds, config.body_radius_H, "haptic cycle (body_radius_H)"),
      contact_cycle_(model, config.dynamics_A, config.dynamics_B, &coherence_) {}

void HapticCycle::Start(std::int64_t now_ns) {
  device_.Read(now_ns, &state_);
  last_sample_ns_ = now_ns;
  coupling_.Reset(state_.X_WD);
  safety_.Start(now_ns);
  if (model_ != nullptr) model_->Reset();
  contact_cycle_.Start(coupling_.X_WH());  // the coherence guard from H's pose, the deformations at rest
  contact_faults_ = 0;
  cycle_ = 0;
}

CycleRecord HapticCycle::Step(std::int64_t now_ns) {
  CycleRecord rec;
  rec.cycle = cycle_;
  rec.now_ns = now_ns;

  // Device pose (the previous one is kept when no new sample arrived).
  rec.new_sample = device_.Read(now_ns, &state_);
  if (rec.new_sample) last_sample_ns_ = now_ns;

  // Contact at the simulated pose of H (body B of the model): the coherence guard (A is static,
  // so H's motion bounds the speed of its points), the deformations held fixed (H deforms: its
  // field at its q), a diverged one restarted instead of queried (contact_cycle.h).
  ContactResult contact;
  if (model_ != nullptr) {
    ContactQuery q;
    q.X_WA = config_.X_WA;
    q.X_WB = coupling_.X_WH();
    q.cycle = cycle_;
    q.node_budget = config_.node_budget;
    ContactCycleQuery done;
    contact = contact_cycle_.Evaluate(q.X_WB, &q, &done);
    rec.point_speed = done.point_speed;
    rec.coherence_reset = done.coherence_reset;
    if (done.queried && config_.point_marks != nullptr) config_.point_marks->Update(*model_, q, cycle_);
  }

  // Static virtual coupling, then the safety filter, then the device. A non-finite contact
  // result does not move H; it reaches the filter as a non-finite wrench (zeroed, counted).
  CouplingStep step;
  if (contact.on_B.force.allFinite() && contact.on_B.torque.allFinite() && contact.K_B.allFinite()) {
    step = coupling_.Update(state_.X_WD, contact.on_B, contact.K_B);
  } else {
    step.X_WH = coupling_.X_WH();
    step.solve_ok = false;
    step.to_device.force.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  const Wrench out = safety_.Filter(step.to_device, now_ns, last_sample_ns_, &rec.safety_flags);
  device_.Write(out, now_ns, rec.safety_flags);

  // Record.
  rec.device_timestamp_ns = state_.timestamp_ns;
  rec.device_sequence = state_.sequence;
  rec.buttons = state_.buttons;
  rec.solve_ok = step.solve_ok;
  rec.points_in_contact = contact.stats.points_in_contact;
  rec.level_rendered = contact.stats.level_rendered;
  rec.nodes_visited = contact.stats.nodes_visited;
  rec.coherence_resets = coherence_.resets();
  rec.contact_fault = contact.stats.faults > 0;
  contact_faults_ += rec.contact_fault ? 1 : 0;
  rec.contact_faults = contact_faults_;
  rec.device_input = device_.input_stats();
  for (int i = 0; i < 3; ++i) {
    rec.p_WD[i] = state_.X_WD.translation[i];
    rec.p_WH[i] = step.X_WH.translation[i];
    rec.contact_force[i] = contact.on_B.force[i];
    rec.device_force[i] = out.force[i];
    rec.device_torque[i] = out.torque[i];
  }
  const Eigen::Quaterniond& qd = state_.X_WD.rotation;
  const Eigen::Quaterniond& qh = step.X_WH.rotation;
  rec.q_WD[0] = qd.w(), rec.q_WD[1] = qd.x(), rec.q_WD[2] = qd.y(), rec.q_WD[3] = qd.z();
  rec.q_WH[0] = qh.w(), rec.q_WH[1] = qh.x(), rec.q_WH[2] = qh.y(), rec.q_WH[3] = qh.z();
  Pose X_WP;
  if (model_ != nullptr && model_->Proxy(&X_WP)) {
    rec.has_proxy = true;
    for (int i = 0; i < 3; ++i) rec.p_WP[i] = X_WP.translation[i];
    rec.q_WP[0] = X_WP.rotation.w(), rec.q_WP[1] = X_WP.rotation.x(), rec.q_WP[2] = X_WP.rotation.y();
    rec.q_WP[3] = X_WP.rotation.z();
  }
  // The deformations advance at the end of the cycle with the contact forces as external
  // loads (paper sec. 4.1 and 5): A's, and H's own, decoupled from H's rigid motion.
  if (model_ != nullptr && contact_cycle_.deformable()) {
    const ContactCycleSteps steps = contact_cycle_.StepDeformations();
    if (config_.dynamics_A != nullptr) rec.q_norm = config_.dynamics_A->state().q.norm();
    if (config_.dynamics_B != nullptr) rec.q_norm_B = config_.dynamics_B->state().q.norm();
    rec.step_ns = steps.step_A_ns + steps.step_B_ns;
  }
  rec.step_ns += contact.stats.step_ns;
  ++cycle_;
  return rec;
}

void HapticCycle::WriteZero(std::int64_t now_ns) { device_.Write(Wrench{}, now_ns, kSafetyNone); }

}  // namespace contactlab
