// A scene of many bodies at run time (docs/scenes.md, "Many bodies"; docs/architecture.md, "The
// scene is a layer of its own"): one asset holder per body, one contact model per pair, FCL's
// dynamic AABB tree as the broad phase, and one cycle over every pair near the tool.
//
// The broad phase. Every body but the tool sits in an FCL DynamicAABBTreeCollisionManager
// (Debian's libfcl) as a box: its mesh's bounding box grown by its surface margin (the offset
// surfaces its pointshell and soup field lie on) and, when deformable, by its deformation bound
// (BodySpec::deformation_bound). Only the tool moves, so the tree is built once at load, like
// Drake's anchored tree; each cycle the tool's box, grown also by what it may travel in a cycle
// (model.max_point_speed times model.cycle_seconds), is placed at the tool's pose and queried
// against it. A pair between two other bodies is near, or not, from load on.
//
// Deformable bodies. After EnableDynamics(dt) each deformable body of a pair steps once per
// cycle (BodyDynamics, its deformable block's integrator and coupling) with the reduced contact
// forces of all its pairs summed; without it every body stays at rest.
//
// Pairs. Each pair has its own model, made at load (the scene's pairs, each in its model's A/B
// order: OrderPair), so its coherence and model state are its own and the cycle makes nothing.
// A pair that stops being near forgets its temporal state (ContactModel::Reset), so it starts
// afresh when it next comes near, and is kept as it is while it stays near.
//
// One budget for the cycle. The scene's node budget (model.node_budget) is shared by the pairs
// near in a cycle, in the order of the scene's pairs: each gets what is left divided by the
// pairs still to go, and never less than an equal share of the whole (a model may overrun its
// share by part of a level), so what a pair leaves unused passes to those after it and a second
// contact site never starves the first. Each pair's
// stats say how far it degraded.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_model.h"
#include "deform/body_dynamics.h"
#include "geometry/aabb.h"
#include "geometry/pose.h"
#include "scene/pair_contact_marks.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"

namespace contactlab {

// What a pair did in the latest cycle.
struct PairOutcome {
  bool near = false;           // its boxes overlapped, so it reached its model
  std::int64_t budget = 0;     // the node budget it was handed (0: unlimited)
  ContactResult result;        // its model's, on the pair's B (zero when not near)
};

struct WorldStats {
  // The pairs' stats together: counts (points in contact, nodes visited, faults, ...) summed,
  // depths and degradation as the largest, the level as the shallowest of the pairs that touched.
  ContactStats sum;
  int pairs = 0;               // in the scene
  int pairs_near = 0;          // whose boxes overlapped
  int pairs_touching = 0;      // whose model found contact
  int pairs_degraded = 0;      // whose model the budget made degrade
  // Deformable bodies displaced past their deformation bound after the cycle's step: the broad
  // phase grew their boxes by that bound, so a pair of theirs may have been missed.
  int bodies_beyond_bound = 0;
};

// The tool's share of a cycle: the wrench on it summed over its pairs (torque about its origin,
// world frame) and its gradient, the 6x6 d(wrench on tool)/d(pose of tool) in the convention of
// ContactResult::K_B, what the static virtual coupling solves with.
struct WorldResult {
  Wrench on_tool;
  Matrix6d K_tool = Matrix6d::Zero();
  WorldStats stats;
};

class SceneWorld {
 public:
  // The bodies and pairs of SCENE, a scene of many bodies (Scene::many_bodies), each pair with
  // its own model or DEFAULT_MODEL. Builds each body's mesh now (for its box) and what its pairs'
  // models need. Throws Error naming the scene's file for a two-body scene, and the pair for a
  // model that cannot be made.
  SceneWorld(const Scene& scene, std::string_view default_model, const AssetOptions& options = {});
  ~SceneWorld();
  SceneWorld(const SceneWorld&) = delete;
  SceneWorld& operator=(const SceneWorld&) = delete;

  const Scene& scene() const { return scene_; }
  int tool() const { return scene_.tool; }
  int body_count() const { return int(bodies_.size()); }
  BodyAssets& body(int i) { return *bodies_[std::size_t(i)]; }
  // The broad-phase box of body I in its body frame (its bounds grown by its margins).
  const Aabb& body_box(int i) const { return boxes_[std::size_t(i)]; }
  int pair_count() const { return int(pairs_.size()); }
  const OrderedPair& pair(int i) const { return pairs_[std::size_t(i)]; }
  ContactModel& model(int i) { return *models_[std::size_t(i)]; }
  const ContactModel& model_const(int i) const { return *models_[std::size_t(i)]; }
  const PairOutcome& outcome(int i) const { return outcomes_[std::size_t(i)]; }
  // The pairs near in the latest cycle, in the order their models were asked.
  std::span<const int> near_pairs() const { return {near_.data(), near_.size()}; }

  // The broad phase alone: the pairs near with the tool at X_W_TOOL (near_pairs()).
  // Allocation-free, throws nothing.
  void FindNearPairs(const Pose& X_W_tool);
  // One cycle with the tool at X_W_TOOL and every other body at its scene pose: the broad phase,
  // then each near pair's model under its share of NODE_BUDGET (< 0: the scene's). CYCLE is the
  // haptic cycle index each pair's model is given. Allocation-free, throws nothing.
  const WorldResult& Evaluate(const Pose& X_W_tool, std::int64_t cycle, std::int64_t node_budget = -1);
  // From now on each Evaluate ends with MARKS.Update (the live view's contacts of every pair);
  // every pair's model keeps up to MARKS.max_contacts() contacts (KeepContacts). Call it outside
  // the cycle: it reserves the memory. MARKS (null: none) must outlive the world's cycles.
  void SetPairContactMarks(PairContactMarks* marks);
  // Forgets every pair's temporal state (the coherence a model keeps between queries); the
  // deformable bodies keep theirs. Allocation-free, throws nothing.
  void ForgetTemporalState();
  // ForgetTemporalState, and every deformable body back at rest.
  void Reset();

  // From now on each deformable body of a pair steps once per cycle of DT seconds (after the
  // queries of Evaluate) with the forces of all its pairs. Throws Error naming the body for a
  // non-positive DT or a model it cannot build.
  void EnableDynamics(double dt);
  // Body I's dynamics, or null (rigid, or dynamics not enabled).
  BodyDynamics* dynamics(int i) { return dynamics_.empty() ? nullptr : dynamics_[std::size_t(i)].get(); }
  // Body I's reduced contact force (and stiffness) of the latest cycle, all its pairs summed, the
  // force its step took; null when it has no dynamics.
  const BodyDeformation* contact_deformation(int i) const {
    return prepared_.empty() ? nullptr : prepared_[std::size_t(i)];
  }

 private:
  struct BroadPhase;
  Scene scene_;
  std::vector<std::unique_ptr<BodyAssets>> bodies_;
  std::vector<Aabb> boxes_;
  std::vector<double> deformation_bounds_;  // per body, what its box was grown by for deformation
  std::vector<OrderedPair> pairs_;
  std::vector<std::unique_ptr<ContactModel>> models_;
  std::vector<PairOutcome> outcomes_;
  std::vector<int> tool_pair_of_body_;  // the pair of the tool with body i, or -1
  std::vector<int> static_near_;        // pairs of two other bodies whose boxes overlap
  std::vector<int> near_, was_near_;    // this cycle's near pairs, and the last cycle's
  std::vector<std::uint8_t> is_near_;   // per pair, this cycle
  std::unique_ptr<BroadPhase> broad_phase_;
  PairContactMarks* pair_marks_ = nullptr;
  WorldResult result_;
  // With dynamics: per body its dynamics and this cycle's deformation (null when rigid); per
  // pair its own reduced forces on its A and B, summed into their bodies after the queries.
  struct PairDeformation {
    ReducedVector force[2];
    ReducedMatrix stiffness[2];
    BodyDeformation deformation[2];
  };
  std::vector<std::unique_ptr<BodyDynamics>> dynamics_;
  std::vector<const BodyDeformation*> prepared_;
  std::vector<PairDeformation> pair_deformations_;
  std::vector<int> deformable_bodies_;
};

// A scene of many bodies as one contact model (docs/scenes.md, "Many bodies"): B is the tool, A
// the world (the query's X_WA is not read); the wrench on B is the wrench on the tool, K_B its
// gradient, the stats the pairs' together (WorldStats::sum). What the haptic cycle of a live
// session closes its loop on: the device moves the tool.
class WorldContactModel final : public ContactModel {
 public:
  WorldContactModel(std::unique_ptr<SceneWorld> world, std::string name)
      : world_(std::move(world)), name_(std::move(name)) {}
  std::string_view name() const override { return name_; }
  ContactResult Evaluate(const ContactQuery& query) override;
  // What a coherence guard asks (the tool moved too fast): every pair's coherence forgotten, the
  // deformable bodies left as they are.
  void Reset() override { world_->ForgetTemporalState(); }
  SceneWorld& world() { return *world_; }

 private:
  std::unique_ptr<SceneWorld> world_;
  std::string name_;
};

// The wrench on body A of a pair and its gradient with respect to A's pose, from the pair's
// result on B (ContactResult: wrench on B about B's origin, K_B with respect to B's pose) at
// world positions p_A and p_B of the bodies' origins: Newton's third law, the torque moved to
// A's origin, and the gradient through the pair's invariance under a rigid motion of both.
void WrenchOnA(const ContactResult& on_B, const Eigen::Vector3d& p_A, const Eigen::Vector3d& p_B, Wrench* on_A,
               Matrix6d* K_A);

}  // namespace contactlab
