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
      coupling_(config.coupling),
      safety_(ResolveSafetyLimits(config.safety, device.capabilities())),
      coherence_(config.max_point_speed, config.cycle_seconds, config.body_radius_H, "haptic cycle (body_radius_H)") {}

void HapticCycle::Start(std::int64_t now_ns) {
  device_.Read(now_ns, &state_);
  last_sample_ns_ = now_ns;
  coupling_.Reset(state_.X_WD);
  safety_.Start(now_ns);
  if (model_ != nullptr) model_->Reset();
  coherence_.Start(coupling_.X_WH());
  contact_faults_ = 0;
  if (config_.dynamics_A != nullptr) config_.dynamics_A->Reset();
  if (config_.dynamics_B != nullptr) config_.dynamics_B->Reset();
  cycle_ = 0;
}

CycleRecord HapticCycle::Step(std::int64_t now_ns) {
  CycleRecord rec;
  rec.cycle = cycle_;
  rec.now_ns = now_ns;

  // Device pose (the previous one is kept when no new sample arrived).
  rec.new_sample = device_.Read(now_ns, &state_);
  if (rec.new_sample) last_sample_ns_ = now_ns;

  // Contact at the simulated pose of H (body B of the model).
  ContactResult contact;
  if (model_ != nullptr) {
    // Temporal-coherence guard: H's motion since the previous query, as a bound on the speed
    // of its points (A is static), against the speed the model's coherence assumes.
    const Pose& X_WH = coupling_.X_WH();
    if (coherence_.Check(X_WH, &rec.point_speed)) {
      model_->ResetCoherence();  // this cycle traverses in full; coherence restarts from it
      rec.coherence_reset = true;
    }
    ContactQuery q;
    q.X_WA = config_.X_WA;
    q.X_WB = X_WH;
    q.cycle = cycle_;
    q.node_budget = config_.node_budget;
    if (config_.dynamics_A != nullptr) q.deformation_A = config_.dynamics_A->Prepare();
    if (config_.dynamics_B != nullptr) q.deformation_B = config_.dynamics_B->Prepare();  // H deforms: its field at its q
    // A deformation that left finite numbers (a diverged step) is not queried.
    if (RestartDiverged({config_.dynamics_A, config_.dynamics_B})) {
      contact = model_->Evaluate(q);
      if (config_.point_marks != nullptr) config_.point_marks->Update(*model_, q, cycle_);
    } else {
      contact.stats.faults = 1;
    }
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
  if (model_ != nullptr && (config_.dynamics_A != nullptr || config_.dynamics_B != nullptr)) {
    const auto t0 = std::chrono::steady_clock::now();
    if (config_.dynamics_A != nullptr) {
      config_.dynamics_A->Step();
      rec.q_norm = config_.dynamics_A->state().q.norm();
    }
    if (config_.dynamics_B != nullptr) {
      config_.dynamics_B->Step();
      rec.q_norm_B = config_.dynamics_B->state().q.norm();
    }
    rec.step_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
  }
  ++cycle_;
  return rec;
}

void HapticCycle::WriteZero(std::int64_t now_ns) { device_.Write(Wrench{}, now_ns, kSafetyNone); }

}  // namespace contactlab
