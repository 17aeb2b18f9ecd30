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
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

struct PointshellContactParams {
  double k_C = 1000;       // contact penalty stiffness, N/m (per point, before L/l scaling)
  int L = 10;              // k_C -> k_C L / l when l >= L points touch; <= 0 disables it
  int level = -1;          // linear variant: tree level rendered (-1: deepest); tree: deepest level allowed
  bool coherence = false;  // tree variant: temporal coherence
  double max_point_speed = 1.0;  // m/s, largest speed of any pointshell point relative to B
  double cycle_seconds = 1e-3;   // duration of one haptic cycle
  double lipschitz = 1.0;  // bound on |grad d| assumed by culling and coherence (paper: 1)
  double cold_fraction = 0.8;    // V_C = cold_fraction * V_W
  ContactGradient gradient = ContactGradient::kHalfspace;
};

class PointshellContactModel final : public ContactModel {
 public:
  enum class Variant { kLinear, kTree };

  // SHELL and FIELD must outlive the model. Throws Error for invalid parameters (k_C < 0,
  // L < 0 treated as disabled, level out of range, non-positive speed or cycle time).
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
