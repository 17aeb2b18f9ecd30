// The paper's contact model against a deformable field body (Barbič & James 2008, sec. 4.2):
// body A's pointshell, rigid or deformable (sec. 4.1), against B's deformed distance field.
// The traversals are those of pointshell_traversal.h; each point's distance comes from the
// proxy-based deformed field at B's reduced coordinates q_B (held fixed during the query).
//
// Forces. A point in contact at x (B's frame) with depth d < 0 and normal N exerts k d N on B
// and the opposite on A, so the total wrench obeys Newton's third law exactly. For B's
// deformation the force is applied at the nearest proxy p of the query (the paper's choice):
// the reduced force on B is k sum d U_p^T N_B, and its halfspace stiffness k sum w w^T with
// w = U_p^T N_B; or, with DeformedFieldOptions::force_at = weighted proxies, w = sum_i w_i
// U_i^T N_B over the query's k proxies. A deformable A receives its reduced force as in
// sec. 4.1.
//
// Culling and temporal coherence assume the field is lipschitz-Lipschitz. The pull-back of a
// compressed region stretches distances by up to |F^{-1}|, so strongly compressed fields need
// a lipschitz above 1. The coherence clock adds the distance B's proxies may have moved since a
// node was culled, sum_j c_j |dq_Bj| with c_j the largest proxy displacement per unit q_j,
// which bounds the motion of the field's surface only as far as the proxies describe it.
#pragma once

#include <memory>
#include <vector>

#include "contact/contact_model.h"
#include "contact/pointshell_contact_model.h"
#include "contact/pointshell_traversal.h"
#include "deform/deformable_pointshell.h"
#include "deform/deformed_distance_field.h"

namespace contactlab {

class DeformedFieldContactModel final : public ContactModel {
 public:
  using Variant = PointshellContactModel::Variant;

  // A is rigid (SHELL) or deformable (DEFORMABLE_SHELL, non-null; SHELL is then ignored).
  // FIELD is B's deformed field. Throws Error as PointshellContactModel does.
  DeformedFieldContactModel(Variant variant, std::shared_ptr<const Pointshell> shell,
                            std::shared_ptr<const DeformablePointshell> deformable_shell,
                            std::shared_ptr<const DeformedDistanceField> field, const PointshellContactParams& params);

  std::string_view name() const override { return variant_ == Variant::kLinear ? "pointshell-linear" : "pointshell"; }
  // One haptic cycle at A's deformation query.q_A (when A deforms) and B's query.q_B (null
  // or another size: at rest). Allocation-free, throws nothing.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // Tree: from the traversal's list of evaluated points; linear: d evaluated again at QUERY's pose
  // (kLinearPointStatesPerCall points per call).
  int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) override;

  const DeformedDistanceField& field() const { return *field_; }
  const DeformedFieldState& field_state() const { return state_; }

 private:
  template <bool kDeformableA>
  ContactResult EvaluateImpl(const ContactQuery& query);

  Variant variant_;
  std::shared_ptr<const Pointshell> shell_;
  std::shared_ptr<const DeformablePointshell> deformable_;  // null: A is rigid
  std::shared_ptr<const DeformedDistanceField> field_;
  PointshellContactParams params_;
  int max_level_;

  DeformedFieldState state_;
  TreeTraversalState traversal_;
  std::vector<double> wake_;       // (#N) coherence clock value at which a culled node wakes
  double travel_ = 0;              // sum over cycles of the deformation travel of A and B, metres
  float previous_qA_[kMaxReducedModes];
  float previous_qB_[kMaxReducedModes];
  bool has_previous_ = false;
};

}  // namespace contactlab
