// The paper's contact model: a pointshell (body A) queried against a signed distance field
// (body B). Barbič & James 2008, sec. 2.1 (per-point penalty forces), sec. 3 (breadth-first
// traversal of the nested point tree, temporal coherence, graceful degradation with warm and
// cold thresholds) and sec. 5 (contact gradient from a halfspace per contact point).
//
// Two variants behind the common interface:
//   "pointshell-linear"  every point of one tree level, no tree (the tree-less reference);
//   "pointshell"         breadth-first traversal culling a subtree when d exceeds the node's
//                        bounding radius, optionally with temporal coherence and a node budget.
// Both bodies are rigid here; DeformablePointshellContactModel deforms body A.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_model.h"
#include "contact/pointshell_contact_params.h"
#include "contact/pointshell_traversal.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {


// Checks what both pointshell models need (a non-empty SHELL and FIELD, valid PARAMS) and
// returns the deepest level they render. Throws Error naming WHERE.
int ValidatePointshellModelInputs(const Pointshell* shell, const DistanceField* field,
                                  const PointshellContactParams& params, const std::string& where);

class PointshellContactModel final : public ContactModel {
 public:
  enum class Variant { kLinear, kTree };

  // SHELL and FIELD must outlive the model. Throws Error for invalid parameters (k_C < 0 or
  // not finite, L < 0, level out of range, non-positive speed or cycle time).
  PointshellContactModel(Variant variant, std::shared_ptr<const Pointshell> shell,
                         std::shared_ptr<const DistanceField> field, const PointshellContactParams& params);

  std::string_view name() const override {
    return variant_ == Variant::kLinear ? "pointshell-linear" : "pointshell";
  }
  // One haptic cycle: allocation-free, throws nothing. query.node_budget (V_W, warm
  // threshold) enables graceful degradation in the tree variant.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // Tree: from the traversal's list of evaluated points; linear: d evaluated again at QUERY's pose
  // (kLinearPointStatesPerCall points per call).
  int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) override;

  const PointshellContactParams& params() const { return params_; }
  const Pointshell& shell() const { return *shell_; }
  const DistanceField& field() const { return *field_; }
  // Deepest level rendered in the previous cycle (tree variant), -1 before the first.
  int last_level_rendered() const { return traversal_.last_level_rendered(); }

 private:
  ContactResult EvaluateLinear(const ContactQuery& query);
  ContactResult EvaluateTree(const ContactQuery& query);

  Variant variant_;
  std::shared_ptr<const Pointshell> shell_;
  std::shared_ptr<const DistanceField> field_;
  PointshellContactParams params_;
  int max_level_;  // deepest level this model renders

  // Scratch sized once at construction.
  TreeTraversalState traversal_;
  std::vector<std::int64_t> earliest_cycle_;  // (#N) temporal coherence
};

}  // namespace contactlab
