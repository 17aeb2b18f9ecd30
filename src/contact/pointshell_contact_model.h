// The paper's contact model: a pointshell (body A) queried against a signed distance field
// (body B). Barbič & James 2008, sec. 2.1 (per-point penalty forces), sec. 3 (breadth-first
// traversal of the nested point tree, temporal coherence, graceful degradation with warm and
// cold thresholds) and sec. 5 (contact gradient from a halfspace per contact point).
//
// Two variants behind the common interface:
//   "pointshell-linear"  every point of one tree level, no tree (the tree-less reference);
//   "pointshell"         breadth-first traversal culling a subtree when d exceeds the node's
//                        bounding radius, optionally with temporal coherence and a node budget.
// Both bodies are rigid here (deformable pointshells and fields come with src/deform).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_model.h"
#include "contact/pointshell_contact_params.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {


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

  const PointshellContactParams& params() const { return params_; }
  const Pointshell& shell() const { return *shell_; }
  const DistanceField& field() const { return *field_; }
  // Deepest level rendered in the previous cycle (tree variant), -1 before the first.
  int last_level_rendered() const { return last_level_rendered_; }

 private:
  ContactResult EvaluateLinear(const ContactQuery& query);
  ContactResult EvaluateTree(const ContactQuery& query);

  Variant variant_;
  std::shared_ptr<const Pointshell> shell_;
  std::shared_ptr<const DistanceField> field_;
  PointshellContactParams params_;
  int max_level_;  // deepest level this model renders

  // Scratch sized once at construction.
  std::vector<std::int32_t> queue_a_, queue_b_;   // (#N) traversal queues
  std::vector<std::uint32_t> point_stamp_;        // (#P) evaluation stamp of each point's d
  std::vector<float> point_d_;                    // (#P) d cached for the stamp
  std::vector<std::int64_t> earliest_cycle_;      // (#N) temporal coherence
  std::uint32_t stamp_ = 0;
  int last_level_rendered_ = -1;
};

}  // namespace contactlab
