// A contact model whose wrench is another model's times a fixed factor s > 0: force, torque
// and the wrench's gradient K_B are multiplied by s, and so are the pressures of its contact
// list and contact surface; positions, normals, depths, areas and stats are the inner model's.
// Every registered model's wrench is linear in its stiffness parameters (k_C of the penalty
// models, the pressure field's modulus, the inner spheres' volume stiffness), so this is the
// same as multiplying those parameters by s, without naming any of them: the scene key
// `model.stiffness: matched` (scene/stiffness_match.h) uses it to put every model at the
// paper's model's stiffness. Allocation-free and throw-free in Evaluate, as the inner model.
#pragma once

#include <memory>
#include <utility>

#include "contact/contact_model.h"

namespace contactlab {

class ScaledContactModel final : public ContactModel {
 public:
  ScaledContactModel(std::unique_ptr<ContactModel> inner, double scale) : inner_(std::move(inner)), scale_(scale) {}

  double scale() const { return scale_; }
  const ContactModel& inner() const { return *inner_; }

  std::string_view name() const override { return inner_->name(); }
  ContactResult Evaluate(const ContactQuery& query) override {
    ContactResult r = inner_->Evaluate(query);
    r.on_B.force *= scale_;
    r.on_B.torque *= scale_;
    r.K_B *= scale_;
    return r;
  }
  void Reset() override { inner_->Reset(); }
  void ResetCoherence() override { inner_->ResetCoherence(); }
  int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) override {
    return inner_->PointStates(query, points, out);
  }
  bool Proxy(Pose* X_WB_proxy) const override { return inner_->Proxy(X_WB_proxy); }
  bool KeepContactSurface(int max_triangles) override { return inner_->KeepContactSurface(max_triangles); }
  void LatestContactSurface(ContactSurface* out) const override {
    inner_->LatestContactSurface(out);
    for (float& p : out->pressure) p = float(p * scale_);
  }
  bool KeepContacts(int max_contacts) override { return inner_->KeepContacts(max_contacts); }
  void LatestContacts(ContactList* out) const override {
    inner_->LatestContacts(out);
    for (double& p : out->pressures) p *= scale_;
  }

 private:
  std::unique_ptr<ContactModel> inner_;
  double scale_;
};

// The factor a ScaledContactModel applies, 1 for any other model.
inline double WrenchScaleOf(const ContactModel& model) {
  const auto* scaled = dynamic_cast<const ScaledContactModel*>(&model);
  return scaled ? scaled->scale() : 1.0;
}

// The model a ScaledContactModel scales, or MODEL itself: where a caller asks a model for a
// capability by its type (contact/volume_fill.h), the scaling must not hide it.
inline const ContactModel& UnscaledOf(const ContactModel& model) {
  const auto* scaled = dynamic_cast<const ScaledContactModel*>(&model);
  return scaled ? scaled->inner() : model;
}

}  // namespace contactlab
