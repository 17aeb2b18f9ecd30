// The paper's contact model with a deformable pointshell (Barbič & James 2008, sec. 4.1): body
// A is a reduced deformable model whose pointshell points sit at x = X + U q, with normals
// from the linear normal correction, against B's rigid distance field. The traversals are the
// rigid model's (pointshell_traversal.h); only the visited points are deformed, and a node's
// radius is the BD-tree bound R(q) = R_0 + sum_j |q_j| rho_j.
//
// Temporal coherence stays conservative under deformation: a culled node sleeps while the
// distance it may have closed, lipschitz * (max_point_speed * elapsed time + sum over cycles
// of sum_j c_j |dq_j|), stays below its margin; c_j (DeformablePointshell::mode_travel) bounds
// how far one unit of q_j moves any point and grows any radius. The deformation part is
// measured from the q of consecutive queries, so it needs no bound on q-dot. As for the rigid
// model, max_point_speed must bound the rigid motion of A's points relative to B.
//
// The contact forces on A's points, F_i = -k d_i N_i (A's frame), become the reduced force
// sum_i U_i^T F_i, written to query.reduced_force_A for the caller's integrator.
#pragma once

#include <memory>
#include <vector>

#include "contact/contact_model.h"
#include "contact/pointshell_contact_model.h"
#include "contact/pointshell_traversal.h"
#include "deform/deformable_pointshell.h"

namespace contactlab {

class DeformablePointshellContactModel final : public ContactModel {
 public:
  using Variant = PointshellContactModel::Variant;

  // SHELL and FIELD are kept alive by the model. Throws Error as PointshellContactModel does.
  DeformablePointshellContactModel(Variant variant, std::shared_ptr<const DeformablePointshell> shell,
                                   std::shared_ptr<const DistanceField> field, const PointshellContactParams& params);

  std::string_view name() const override {
    return variant_ == Variant::kLinear ? "pointshell-linear" : "pointshell";
  }
  // One haptic cycle at A's deformation query.q_A (r entries; null or another size: at
  // rest). Allocation-free, throws nothing.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // Tree: from the traversal's list of evaluated points; linear: d evaluated again at QUERY's pose
  // (kLinearPointStatesPerCall points per call).
  int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) override;

  const DeformablePointshell& deformable_shell() const { return *shell_; }
  int r() const { return shell_->r(); }
  int last_level_rendered() const { return traversal_.last_level_rendered(); }

 private:
  Variant variant_;
  std::shared_ptr<const DeformablePointshell> shell_;
  std::shared_ptr<const DistanceField> field_;
  PointshellContactParams params_;
  int max_level_;

  TreeTraversalState traversal_;
  std::vector<double> wake_;            // (#N) coherence clock value at which a culled node wakes
  double deformation_travel_ = 0;       // sum over cycles of sum_j c_j |dq_j|, metres
  float previous_q_[kMaxReducedModes];  // q of the previous query
  bool has_previous_q_ = false;
};

}  // namespace contactlab
