#include "scene/scene_world.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "contact/model_registry.h"
#include "contact/register_contact_models.h"
#include "geometry/triangle_mesh.h"
#include "util/error.h"

namespace contactlab {
namespace {

Eigen::Matrix3d Cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// How far outside its mesh a body's contact surfaces may lie: its pointshell's offset surface
// (half a field spacing by default) and a soup field's iso-offset (1.5 spacings by default), or
// the offsets the scene gives; two spacings of its field cover the defaults.
double SurfaceMargin(const BodySpec& spec, const Aabb& bounds) {
  const double extent = bounds.size().maxCoeff();
  const double spacing = extent * (1 + 2 * spec.field.padding) / std::max(1, spec.field.resolution);
  return std::max({2 * spacing, spec.pointshell.offset, spec.field.offset});
}

// The bound on how far a body's surface moves: its own, else a tenth of its largest half-extent
// when it deforms; 0 when rigid.
double DeformationBound(const BodySpec& spec, const Aabb& bounds) {
  if (!spec.deformable) return 0;
  if (spec.deformation_bound >= 0) return spec.deformation_bound;
  return 0.05 * bounds.size().maxCoeff();
}

fcl::Transform3d BoxTransform(const Pose& X_W, const Aabb& box) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = X_W.rotation.toRotationMatrix();
  t.translation() = X_W * box.center();
  return t;
}

}  // namespace

void WrenchOnA(const ContactResult& on_B, const Eigen::Vector3d& p_A, const Eigen::Vector3d& p_B, Wrench* on_A,
               Matrix6d* K_A) {
  const Eigen::Vector3d& F = on_B.on_B.force;
  const Eigen::Vector3d& tau = on_B.on_B.torque;
  const Eigen::Vector3d r = p_B - p_A;
  on_A->force = -F;
  on_A->torque = -tau - r.cross(F);
  // Moving A by (dx, dθ) is moving both bodies by that rigid motion about p_A, then B back by
  // its inverse, which moves B by -T (dx, dθ), T = [I, -[r]x; 0, I]; the first motion turns the
  // wrench on B with it. So d(wrench on B)/d(pose of A) = -K_B T - [0, [F]x; 0, [τ]x].
  Matrix6d T = Matrix6d::Identity();
  T.block<3, 3>(0, 3) = -Cross(r);
  Matrix6d M = -on_B.K_B * T;
  M.block<3, 3>(0, 3) -= Cross(F);
  M.block<3, 3>(3, 3) -= Cross(tau);
  // Force on A = -F; torque on A about p_A = -τ - r x F, where r = p_B - p_A moves by -dx.
  K_A->topRows<3>() = -M.topRows<3>();
  K_A->bottomRows<3>() = -M.bottomRows<3>() - Cross(r) * M.topRows<3>();
  K_A->block<3, 3>(3, 0) -= Cross(F);
}

// FCL's dynamic AABB tree over every body but the tool, and the tool's box that queries it.
struct SceneWorld::BroadPhase {
  fcl::DynamicAABBTreeCollisionManagerd tree;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;  // per body (the tool's not in the tree)
  Aabb tool_box;                                                // body frame
  struct Query {
    SceneWorld* world;
  };

  // FCL calls this for each body whose box overlaps the tool's: its pair, if any, is near.
  static bool Near(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
    SceneWorld& w = *static_cast<Query*>(data)->world;
    for (fcl::CollisionObjectd* o : {a, b}) {
      const int body = int(reinterpret_cast<std::intptr_t>(o->getUserData())) - 1;
      if (body == w.scene_.tool) continue;
      const int pair = w.tool_pair_of_body_[std::size_t(body)];
      if (pair >= 0 && !w.is_near_[std::size_t(pair)]) {
        w.is_near_[std::size_t(pair)] = 1;
        w.near_.push_back(pair);
      }
    }
    return false;  // go on
  }
};

SceneWorld::SceneWorld(const Scene& scene, std::string_view default_model, const AssetOptions& options)
    : scene_(scene), broad_phase_(std::make_unique<BroadPhase>()) {
  RegisterContactModels();
  if (!scene_.many_bodies()) {
    Fail(scene_.file.empty() ? std::string("scene") : scene_.file,
         "a scene of two bodies without `tool:` has no pairs to hold (its one pair is the scene itself)");
  }
  AssetOptions o = options;
  if (o.mesh_dir.empty() && !scene_.file.empty()) o.mesh_dir = FolderOf(scene_.file);
  const int n = int(scene_.bodies.size());
  for (const BodySpec& b : scene_.bodies) bodies_.push_back(std::make_unique<BodyAssets>(b, o));
  // Each body's box: its mesh's bounds grown by its margins; the tool's also by a cycle's travel.
  const double travel = scene_.model.max_point_speed * scene_.model.cycle_seconds;
  for (int i = 0; i < n; ++i) {
    const Aabb bounds = bodies_[std::size_t(i)]->mesh()->Bounds();
    const BodySpec& spec = scene_.bodies[std::size_t(i)];
    deformation_bounds_.push_back(DeformationBound(spec, bounds));
    const double grow = SurfaceMargin(spec, bounds) + deformation_bounds_.back() + (i == scene_.tool ? travel : 0);
    Aabb box = bounds;
    box.min.array() -= grow;
    box.max.array() += grow;
    boxes_.push_back(box);
    const Eigen::Vector3d size = box.size();
    auto object = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z()),
                                                          BoxTransform(spec.pose, box));
    object->setUserData(reinterpret_cast<void*>(std::intptr_t(i + 1)));
    object->computeAABB();
    broad_phase_->objects.push_back(std::move(object));
  }
  std::vector<fcl::CollisionObjectd*> others;
  for (int i = 0; i < n; ++i) {
    if (i != scene_.tool) others.push_back(broad_phase_->objects[std::size_t(i)].get());
  }
  broad_phase_->tree.registerObjects(others);
  broad_phase_->tree.setup();
  // Each pair's model, in its A/B order.
  tool_pair_of_body_.assign(std::size_t(n), -1);
  for (const PairSpec& spec : scene_.pairs) {
    const OrderedPair p = OrderPair(scene_, spec, default_model);
    const ContactParams& params = spec.has_params ? spec.params : scene_.model;
    if (params.stiffness != StiffnessRule::kOwn) {
      Fail(spec.where, "model.stiffness: matched is for scenes of two bodies (it presses the one pair to a reference "
                       "depth); give each pair's stiffness keys");
    }
    const ParamValues& model_params = spec.has_params ? spec.model_params : scene_.model_params;
    models_.push_back(MakeContactModel(
        p.model, ContactModelInputs{*bodies_[std::size_t(p.A)], *bodies_[std::size_t(p.B)], params, model_params},
        spec.where));
    const int index = int(pairs_.size());
    pairs_.push_back(p);
    if (p.A == scene_.tool) tool_pair_of_body_[std::size_t(p.B)] = index;
    if (p.B == scene_.tool) tool_pair_of_body_[std::size_t(p.A)] = index;
    if (p.A != scene_.tool && p.B != scene_.tool) {
      const fcl::AABBd& a = broad_phase_->objects[std::size_t(p.A)]->getAABB();
      const fcl::AABBd& b = broad_phase_->objects[std::size_t(p.B)]->getAABB();
      if (a.overlap(b)) static_near_.push_back(index);
    }
  }
  outcomes_.resize(pairs_.size());
  is_near_.assign(pairs_.size(), 0);
  near_.reserve(pairs_.size());
  was_near_.reserve(pairs_.size());
  result_.stats.pairs = int(pairs_.size());
}

SceneWorld::~SceneWorld() = default;

void SceneWorld::FindNearPairs(const Pose& X_W_tool) {
  was_near_.assign(near_.begin(), near_.end());
  for (const int p : near_) is_near_[std::size_t(p)] = 0;
  near_.clear();
  fcl::CollisionObjectd& tool = *broad_phase_->objects[std::size_t(scene_.tool)];
  tool.setTransform(BoxTransform(X_W_tool, boxes_[std::size_t(scene_.tool)]));
  tool.computeAABB();
  BroadPhase::Query query{this};
  broad_phase_->tree.collide(&tool, &query, &BroadPhase::Near);
  for (const int p : static_near_) {
    is_near_[std::size_t(p)] = 1;
    near_.push_back(p);
  }
  // The scene's order, so the budget is shared the same way whatever order FCL found them in.
  std::sort(near_.begin(), near_.end());
  // A pair no longer near forgets its temporal state and its latest result.
  for (const int p : was_near_) {
    if (!is_near_[std::size_t(p)]) {
      models_[std::size_t(p)]->Reset();
      outcomes_[std::size_t(p)] = PairOutcome{};
    }
  }
}

void SceneWorld::EnableDynamics(double dt) {
  dynamics_.clear();
  dynamics_.resize(bodies_.size());
  prepared_.assign(bodies_.size(), nullptr);
  deformable_bodies_.clear();
  for (int b = 0; b < body_count(); ++b) {
    if (!bodies_[std::size_t(b)]->deformable()) continue;
    // Staggered when a pair presses it against another deformable body (BodyDynamics).
    bool staggered = false, paired = false;
    for (const OrderedPair& p : pairs_) {
      if (p.A != b && p.B != b) continue;
      paired = true;
      const int other = p.A == b ? p.B : p.A;
      staggered = staggered || bodies_[std::size_t(other)]->deformable();
    }
    if (!paired) continue;
    dynamics_[std::size_t(b)] = MakeBodyDynamics(*bodies_[std::size_t(b)], dt, staggered);
    deformable_bodies_.push_back(b);
  }
  pair_deformations_.assign(pairs_.size(), PairDeformation{});
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const int sides[2] = {pairs_[p].A, pairs_[p].B};
    for (int s = 0; s < 2; ++s) {
      BodyDynamics* d = dynamics_[std::size_t(sides[s])].get();
      if (d == nullptr) continue;
      PairDeformation& pd = pair_deformations_[p];
      pd.force[s].setZero(d->r());
      pd.stiffness[s].setZero(d->r(), d->r());
      pd.deformation[s] = {&d->state(), &pd.force[s], d->implicit_contact() ? &pd.stiffness[s] : nullptr};
    }
  }
}

const WorldResult& SceneWorld::Evaluate(const Pose& X_W_tool, std::int64_t cycle, std::int64_t node_budget) {
  FindNearPairs(X_W_tool);
  // Each deformable body's force and stiffness zeroed for this cycle; a diverged one from rest.
  for (const int b : deformable_bodies_) {
    BodyDynamics& d = *dynamics_[std::size_t(b)];
    (void)RestartDiverged({&d});
    prepared_[std::size_t(b)] = d.Prepare();
  }
  const std::int64_t budget = node_budget < 0 ? scene_.node_budget : node_budget;
  WorldResult& out = result_;
  out.on_tool = Wrench{};
  out.K_tool.setZero();
  WorldStats& s = out.stats;
  s = WorldStats{};
  s.pairs = int(pairs_.size());
  s.pairs_near = int(near_.size());
  std::int64_t left = budget;
  for (std::size_t k = 0; k < near_.size(); ++k) {
    const int p = near_[k];
    const OrderedPair& pair = pairs_[std::size_t(p)];
    ContactQuery q;
    q.X_WA = pair.A == scene_.tool ? X_W_tool : scene_.bodies[std::size_t(pair.A)].pose;
    q.X_WB = pair.B == scene_.tool ? X_W_tool : scene_.bodies[std::size_t(pair.B)].pose;
    q.cycle = cycle;
    // What is left over the pairs still to go, and never less than an equal share: a model that
    // overran its share (by part of a level) does not starve the pairs after it.
    if (budget > 0) {
      const std::int64_t equal = budget / std::int64_t(near_.size());
      q.node_budget = std::max<std::int64_t>({1, equal, left / std::int64_t(near_.size() - k)});
    }
    PairDeformation* pd = pair_deformations_.empty() ? nullptr : &pair_deformations_[std::size_t(p)];
    if (pd != nullptr) {
      for (int side = 0; side < 2; ++side) {
        if (pd->deformation[side].force == nullptr) continue;
        pd->force[side].setZero();
        pd->stiffness[side].setZero();
      }
      if (pd->deformation[0].force != nullptr) q.deformation_A = &pd->deformation[0];
      if (pd->deformation[1].force != nullptr) q.deformation_B = &pd->deformation[1];
    }
    PairOutcome& o = outcomes_[std::size_t(p)];
    o.near = true;
    o.budget = q.node_budget;
    o.result = models_[std::size_t(p)]->Evaluate(q);
    const ContactStats& st = o.result.stats;
    if (budget > 0) left = std::max<std::int64_t>(0, left - st.nodes_visited);
    // The pair's reduced forces onto its deformable bodies.
    if (pd != nullptr) {
      const int sides[2] = {pair.A, pair.B};
      for (int side = 0; side < 2; ++side) {
        const BodyDeformation* into = prepared_[std::size_t(sides[side])];
        if (pd->deformation[side].force == nullptr || into == nullptr) continue;
        *into->force += pd->force[side];
        if (into->stiffness != nullptr) *into->stiffness += pd->stiffness[side];
      }
    }
    ContactStats& sum = s.sum;
    sum.points_in_contact += st.points_in_contact;
    sum.nodes_visited += st.nodes_visited;
    sum.nodes_skipped_coherence += st.nodes_skipped_coherence;
    sum.faults += st.faults;
    sum.contact_area += st.contact_area;
    sum.patches += st.patches;
    sum.degraded = std::max(sum.degraded, st.degraded);
    sum.max_penetration = std::max(sum.max_penetration, st.max_penetration);
    if (st.points_in_contact > 0 && st.level_rendered >= 0) {
      sum.level_rendered = sum.level_rendered < 0 ? st.level_rendered : std::min(sum.level_rendered, st.level_rendered);
    }
    if (st.points_in_contact > 0) ++s.pairs_touching;
    if (st.degraded > 0) ++s.pairs_degraded;
    if (pair.B == scene_.tool) {
      out.on_tool.force += o.result.on_B.force;
      out.on_tool.torque += o.result.on_B.torque;
      out.K_tool += o.result.K_B;
    } else if (pair.A == scene_.tool) {
      Wrench w;
      Matrix6d K;
      WrenchOnA(o.result, q.X_WA.translation, q.X_WB.translation, &w, &K);
      out.on_tool.force += w.force;
      out.on_tool.torque += w.torque;
      out.K_tool += K;
    }
  }
  // Each deformable body steps once, with the forces of all its pairs.
  const auto t0 = std::chrono::steady_clock::now();
  for (const int b : deformable_bodies_) dynamics_[std::size_t(b)]->Step();
  if (!deformable_bodies_.empty()) {
    s.sum.step_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count();
  }
  // A body deformed past the bound its box was grown by may touch a body the broad phase kept
  // apart: counted (the mesh pass runs only when the cheap bound from ||q|| is over).
  s.bodies_beyond_bound = 0;
  for (const int b : deformable_bodies_) {
    BodyDynamics& d = *dynamics_[std::size_t(b)];
    const double bound = deformation_bounds_[std::size_t(b)];
    if (d.MaxDisplacementBound() > bound && d.MaxDisplacement() > bound) ++s.bodies_beyond_bound;
  }
  if (pair_marks_ != nullptr) pair_marks_->Update(*this, cycle);
  return out;
}

ContactResult WorldContactModel::Evaluate(const ContactQuery& query) {
  const WorldResult& r = world_->Evaluate(query.X_WB, query.cycle, query.node_budget);
  ContactResult out;
  out.on_B = r.on_tool;
  out.K_B = r.K_tool;
  out.stats = r.stats.sum;
  return out;
}

void SceneWorld::SetPairContactMarks(PairContactMarks* marks) {
  pair_marks_ = marks;
  if (marks == nullptr) return;
  for (auto& m : models_) (void)m->KeepContacts(marks->max_contacts());
}

void SceneWorld::ForgetTemporalState() {
  for (auto& m : models_) m->Reset();
  for (PairOutcome& o : outcomes_) o = PairOutcome{};
  for (const int p : near_) is_near_[std::size_t(p)] = 0;
  near_.clear();
  was_near_.clear();
}

void SceneWorld::Reset() {
  ForgetTemporalState();
  for (const int b : deformable_bodies_) dynamics_[std::size_t(b)]->Reset();
}

}  // namespace contactlab
