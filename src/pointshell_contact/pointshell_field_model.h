// The paper's contact model (Barbič & James 2008): a pointshell (body A) against a signed
// distance field (body B), with per-point penalty forces (sec. 2.1), the breadth-first traversal
// of the nested point tree with temporal coherence and graceful degradation (sec. 3), the
// halfspace contact gradient (sec. 5) and, for deformable bodies, reduced contact forces
// (sec. 4). One class template over two sides:
//
//   shell side   RigidShell | DeformableShell         (contact/rigid_sides.h, deformable_sides.h)
//   field side   GridField  | DeformedField
//
// so that no point pays a virtual call or an "is deformable?" branch: the rigid x grid instance
// is the rigid loop alone. Two variants behind the common interface:
//   "pointshell-linear"  every point of one tree level, no tree (the tree-less reference);
//   "pointshell"         breadth-first traversal culling a subtree when d exceeds the node's
//                        bounding radius, optionally with temporal coherence and a node budget.
//
// Temporal coherence: the clock reads the distance any point may have closed on B by rigid
// motion since the first query, lipschitz * max_point_speed * elapsed time; a culled node whose
// ball was MARGIN clear of contact sleeps until the clock has advanced by MARGIN. A deformable
// shell adds the node's own deformation bound, lipschitz * sum_j c_nj |q_j - q_j at its sleep|
// (DeformableShell::Travel): path-independent, and small for a node whose region hardly moves
// with q, so a small change of q wakes only the nodes it can bring into contact.
// max_point_speed must bound the rigid motion of A's points relative to B. Against a deformed
// field coherence is refused (an Error at construction): no cheap bound covers how fast its
// distances can drop (a point pulled back through a proxy's deformation gradient moves with
// its distance from the proxy, and the eq. (3) weights shift between proxies, so its distances
// drop by many times the proxies' travel; DeformedFieldContact test).
//
// Contacts (KeepContacts / LatestContacts): one per point in contact (d < 0), so as many as
// stats.points_in_contact: the point's world position (deformed when A deforms), the direction
// of its force on B, -N (N: the point's inward normal, corrected when A deforms, in the world),
// and its depth -d (metres) in B's field as the query looked it up. The force on B is the sum
// over them of k depth normal, k = k_C * stats.stiffness_scale (sec. 2.1, eq. (1)).
//
// Friction (contact/friction.h; rigid bodies: a scene asking for it with a deformable side is
// refused): each point in contact holds an anchor in B's frame from its first touch until it
// leaves contact (its index is the anchor's); its tangential force adds to the wrench with the
// same stiffness k as its normal force. Under graceful degradation a point that the previous
// cycle's level left out, and so has no anchor, takes over the displacement of its parent
// node's point when the level deepens (its anchor passes to its children); the points of the
// levels kept keep theirs. Contacts list each point's friction force and whether it sticks.
//
// Forces: every point in contact is added through the vectorised halfspace sums
// (contact/halfspace_contacts.h), a buffer at a time; for a deformable side the same runs of
// points also enter its reduced force (and its halfspace stiffness). ContactGradient::kField
// adds each point on its own, with the field side's gradient.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_model.h"
#include "contact/contact_recorder.h"
#include "contact/float_transform.h"
#include "contact/friction.h"
#include "contact/halfspace_contacts.h"
#include "pointshell_contact/pointshell_contact_params.h"
#include "pointshell_contact/pointshell_traversal.h"
#include "pointshell_contact/reduced_force_sum.h"
#include "util/error.h"

namespace contactlab {

enum class PointshellVariant { kLinear, kTree };

// Checks what the model needs (a non-empty SHELL and FIELD, valid PARAMS) and returns the
// deepest level it renders. Throws Error naming WHERE.
int ValidatePointshellModelInputs(const Pointshell* shell, const DistanceField* field,
                                  const PointshellContactParams& params, const std::string& where);
// Throws Error naming WHERE when PARAMS ask the VARIANT for temporal coherence against a field
// side that deforms (FIELD_DEFORMS): not conservative there (see above). The model's
// constructor and its registry entry's check (what an experiment config is checked by before
// anything is built) both apply it.
void CheckPointshellCoherence(const PointshellContactParams& params, PointshellVariant variant, bool field_deforms,
                              std::string_view where);

template <class Shell, class Field>
class PointshellFieldModel final : public ContactModel {
 public:
  using Variant = PointshellVariant;
  static constexpr bool kDeforms = Shell::kDeforms || Field::kDeforms;

  // SHELL and FIELD are kept alive by the model. Throws Error for a missing or empty shell or
  // field and invalid parameters (k_C < 0 or not finite, L < 0, level out of range,
  // non-positive speed or cycle time).
  PointshellFieldModel(Variant variant, typename Shell::Source shell, typename Field::Source field,
                       const PointshellContactParams& params)
      : variant_(variant), shell_(std::move(shell)), field_(std::move(field)), params_(params) {
    const std::string where = std::string("contact model ") + std::string(name()) + " (" + Shell::kWhat + " against " +
                              Field::kWhat + ")";
    max_level_ = ValidatePointshellModelInputs(shell_.get(), field_.rest_field_ptr(), params_, where);
    CheckPointshellCoherence(params_, variant_, Field::kDeforms, where);
    const Pointshell& s = shell_.shell();
    traversal_ = TreeTraversalState(s);
    wake_.assign(std::size_t(s.num_nodes()), -std::numeric_limits<double>::infinity());
    if constexpr (Shell::kDeforms) {
      sleep_stamp_.assign(std::size_t(s.num_nodes()), 0u);
      for (auto* v : {&x_, &y_, &z_, &nx_, &ny_, &nz_}) v->assign(std::size_t(s.num_points()), 0.f);
    }
    if constexpr (Field::kDeforms) nearest_.assign(std::size_t(s.num_points()), -1);
    if (params_.friction.on()) {
      if constexpr (kDeforms) {
        Fail(where, "friction is carried between rigid bodies only (set friction.static: 0)");
      } else {
        anchors_ = FrictionAnchors(s.num_points());
        parent_point_.assign(std::size_t(s.num_points()), -1);
        for (int n = 0; n < s.num_nodes(); ++n) {
          for (std::int32_t c = s.child_begin[n] + 1; c < s.child_begin[n + 1]; ++c) {
            parent_point_[std::size_t(s.node_point[c])] = s.node_point[n];
          }
        }
      }
    }
  }

  std::string_view name() const override { return variant_ == Variant::kLinear ? "pointshell-linear" : "pointshell"; }
  // One haptic cycle: allocation-free, throws nothing. query.node_budget (V_W, warm threshold)
  // enables graceful degradation in the tree variant. A deformation of the wrong size for its
  // body gives no force and stats.faults = 1.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {
    ResetCoherence();
    anchors_.Reset();
  }
  // Coherence and the level hysteresis; friction anchors are no such shortcut and stay.
  void ResetCoherence() override {
    std::fill(wake_.begin(), wake_.end(), -std::numeric_limits<double>::infinity());
    traversal_.Reset();
  }
  // Tree: from the traversal's list of evaluated points; linear: d evaluated again at QUERY's
  // pose and A's deformation, in B's field as the latest query left it (kLinearPointStatesPerCall
  // points per call).
  int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) override;
  // The points in contact (see the top of this file), recorded during Evaluate.
  bool KeepContacts(int max_contacts) override {
    contacts_.Keep(max_contacts, false, params_.friction.on());
    return true;
  }
  void LatestContacts(ContactList* out) const override { contacts_.Fill(X_WB_contacts_, 1.0, out); }

  const PointshellContactParams& params() const { return params_; }
  const Pointshell& shell() const { return shell_.shell(); }
  // Deepest level rendered in the previous cycle (tree variant), -1 before the first.
  int last_level_rendered() const { return traversal_.last_level_rendered(); }

 private:
  struct Pass;

  Variant variant_;
  Shell shell_;
  Field field_;
  PointshellContactParams params_;
  int max_level_;  // deepest level this model renders

  // Scratch sized once at construction.
  TreeTraversalState traversal_;
  std::vector<double> wake_;  // (#N) coherence clock value at which a culled node wakes
  std::vector<std::uint32_t> sleep_stamp_;  // (#N) a deformable shell's stamp when the node slept
  // A deformable shell's points in contact this query: deformed position and corrected normal
  // (A's frame), written at the point's index (#P each).
  std::vector<float> x_, y_, z_, nx_, ny_, nz_;
  std::vector<std::int32_t> nearest_;  // (#P) a deformed field's proxy slot of each point in contact
  // Friction on: each point's anchor, and the point of its node's parent (-1: a root's point, or
  // the same point one level up).
  FrictionAnchors anchors_;
  std::vector<std::int32_t> parent_point_;  // (#P)
  // The contacts of the latest Evaluate, in B's frame, when kept, and B's pose then.
  ContactRecorder contacts_;
  Pose X_WB_contacts_;
};

// One query's traversal policy (pointshell_traversal.h): evaluates points a batch at a time and
// adds the forces of those in contact.
template <class Shell, class Field>
struct PointshellFieldModel<Shell, Field>::Pass {
  PointshellFieldModel& m;
  const Pointshell& s;
  const FloatTransform X_BA;
  ContactAccumulator* acc;
  HalfspaceContactBuffer* contacts;  // the halfspace rule's buffer, null under kField
  ReducedForceSum* sum_A;            // A's reduced force, or null
  ReducedForceSum* sum_B;            // B's, or null
  double clock;  // the coherence clock of this query, metres
  FrictionSums* friction = nullptr;  // friction on: the query's friction sums
  // Friction on: points from this index on were left out by the previous cycle's level, and take
  // over their parent's displacement at first touch.
  int inherit_begin = std::numeric_limits<int>::max();
  Eigen::Vector3d last_u = Eigen::Vector3d::Zero();  // the latest Rub's displacement and state
  bool last_sliding = false;

  // Where the points in contact are found: the shell's own arrays, or the deformed ones.
  ContactPointArrays Points() const {
    if constexpr (Shell::kDeforms) {
      return {m.x_.data(), m.y_.data(), m.z_.data(), m.nx_.data(), m.ny_.data(), m.nz_.data()};
    } else {
      return ContactPointArrays::Of(s);
    }
  }

  void EvaluatePoints(int begin, const std::int32_t* index, int n, float* d) {
    if constexpr (!kDeforms) {  // the rigid loop: one batch of lookups, then the contacts
      const int offset = index ? 0 : begin;
      m.field_.Distances(X_BA, s.x.data() + offset, s.y.data() + offset, s.z.data() + offset, index, n, d, nullptr);
      if (m.contacts_.keeping() || friction != nullptr) [[unlikely]] {
        for (int k = 0; k < n; ++k) {
          if (!(d[k] < 0.f)) continue;
          const int i = index ? index[k] : begin + k;
          if (friction != nullptr) Rub(i, d[k]);
          if (m.contacts_.keeping()) Record(i, d[k]);
        }
      }
      if (contacts != nullptr) {
        contacts->Collect(begin, index, d, n);
      } else {
        for (int k = 0; k < n; ++k) {
          if (d[k] < 0.f) [[unlikely]] AddOnItsOwn(index ? index[k] : begin + k, d[k]);
        }
      }
    } else {
      constexpr int kChunk = 256;
      float px[kChunk], py[kChunk], pz[kChunk];
      std::int32_t nearest[kChunk];
      for (int c0 = 0; c0 < n; c0 += kChunk) {
        const int mk = std::min(kChunk, n - c0);
        const std::int32_t* idx = index ? index + c0 : nullptr;
        const int first = begin + c0;  // the chunk's first point when IDX is null
        // 1. Distances of the chunk's points (deformed first when A deforms).
        if constexpr (Shell::kDeforms) {
          m.shell_.Positions(idx, first, mk, px, py, pz);
          m.field_.Distances(X_BA, px, py, pz, nullptr, mk, d + c0, nearest);
        } else {
          const int offset = idx ? 0 : first;
          m.field_.Distances(X_BA, s.x.data() + offset, s.y.data() + offset, s.z.data() + offset, idx, mk, d + c0,
                             nearest);
        }
        // 2. What the points in contact need later: position, normal (a batch of them), proxy.
        std::int32_t hit[kChunk];
        float hit_d[kChunk];
        int hits = 0;
        for (int k = 0; k < mk; ++k) {
          if (!(d[c0 + k] < 0.f)) [[likely]] continue;
          const int i = idx ? idx[k] : first + k;
          if constexpr (Shell::kDeforms) m.x_[i] = px[k], m.y_[i] = py[k], m.z_[i] = pz[k];
          if constexpr (Field::kDeforms) m.nearest_[i] = nearest[k];
          hit_d[hits] = d[c0 + k];
          hit[hits++] = i;
        }
        if constexpr (Shell::kDeforms) {
          float hx[kChunk], hy[kChunk], hz[kChunk];
          m.shell_.Normals(hit, hits, hx, hy, hz);
          for (int h = 0; h < hits; ++h) m.nx_[hit[h]] = hx[h], m.ny_[hit[h]] = hy[h], m.nz_[hit[h]] = hz[h];
        }
        if (m.contacts_.keeping()) [[unlikely]] {
          for (int h = 0; h < hits; ++h) Record(hit[h], hit_d[h]);
        }
        if (contacts == nullptr) {
          for (int h = 0; h < hits; ++h) AddOnItsOwn(hit[h], hit_d[h]);
        }
        // 3. Their forces, a buffer at a time.
        if (contacts != nullptr) contacts->Collect(first, idx, d + c0, mk);
      }
    }
  }

  // Point I in contact at D < 0, kept for LatestContacts: in B's frame, the force's direction
  // on B (-N_B) and the depth -D.
  void Record(int i, float d) {
    const ContactPointArrays P = Points();
    float p_B[3], n_B[3];
    X_BA.Apply(P.x[i], P.y[i], P.z[i], p_B);
    X_BA.Rotate(P.nx[i], P.ny[i], P.nz[i], n_B);
    const Eigen::Vector3d N_B(n_B[0], n_B[1], n_B[2]);
    m.contacts_.Add(Eigen::Vector3d(p_B[0], p_B[1], p_B[2]), -N_B.normalized(), -double(d));
    if (friction != nullptr) m.contacts_.AddFriction(-double(d) * last_u, !last_sliding);
  }
  // Point I's position and unit inward normal in B's frame.
  Eigen::Vector3d PointInB(const ContactPointArrays& P, int i) const {
    float p_B[3];
    X_BA.Apply(P.x[i], P.y[i], P.z[i], p_B);
    return {p_B[0], p_B[1], p_B[2]};
  }
  // Rigid point I in contact at depth D < 0 with friction on: its anchor's update and its
  // friction terms (contact/friction.h), in the gradient the query's rule asks for.
  void Rub(int i, float d) {
    const ContactPointArrays P = Points();
    float n_B[3];
    X_BA.Rotate(P.nx[i], P.ny[i], P.nz[i], n_B);
    const Eigen::Vector3d p = PointInB(P, i);
    const Eigen::Vector3d N(n_B[0], n_B[1], n_B[2]);  // unit: the shell's normals rotated
    FrictionAnchors& anchors = m.anchors_;
    Eigen::Vector3d inherit = Eigen::Vector3d::Zero();
    if (i >= inherit_begin && !anchors.Alive(i)) {
      const std::int32_t parent = m.parent_point_[std::size_t(i)];
      if (parent >= 0 && anchors.Alive(parent)) inherit = PointInB(P, parent) - anchors.anchor(parent);
    }
    Eigen::Vector3d g = N;
    if constexpr (!kDeforms) {
      if (params().gradient == ContactGradient::kField) g = m.field_.Gradient(p);
    }
    last_sliding = AddFrictionContact(&anchors, friction, params().friction, i, p, N, -double(d), g, &last_u, inherit);
  }
  // Point I in contact at depth D under kField: its force, gradient and reduced forces.
  void AddOnItsOwn(int i, float d) {
    const ContactPointArrays P = Points();
    float p_B[3], n_B[3];
    X_BA.Apply(P.x[i], P.y[i], P.z[i], p_B);
    const float n_A[3] = {P.nx[i], P.ny[i], P.nz[i]};
    AddContactPointWith(X_BA, n_A, p_B, d, params().gradient, acc,
                        [this](const Eigen::Vector3d& p) { return m.field_.Gradient(p); }, n_B);
    const std::int32_t index = i;
    AddReduced(&index, &d, 1);
  }
  // Points INDEX[k], k < N, in contact at depths D[k]: their part of each deformable side's
  // reduced force.
  void AddReduced(const std::int32_t* index, const float* d, int n) {
    if constexpr (kDeforms) {
      const ContactPointArrays P = Points();
      if constexpr (Shell::kDeforms) {
        if (sum_A != nullptr) m.shell_.AddReduced(P.nx, P.ny, P.nz, index, d, n, sum_A);
      }
      if constexpr (Field::kDeforms) {
        if (sum_B != nullptr) {
          for (int k = 0; k < n; ++k) {
            const int i = index[k];
            float p_B[3], n_B[3];
            X_BA.Apply(P.x[i], P.y[i], P.z[i], p_B);
            X_BA.Rotate(P.nx[i], P.ny[i], P.nz[i], n_B);
            m.field_.AddReduced(m.nearest_[i], p_B, n_B, d[k], sum_B);
          }
        }
      }
    }
  }
  // HalfspaceContactBuffer's flush hook: the reduced forces of a run of points added.
  static void OnFlush(void* self, const std::int32_t* index, const float* d, int n) {
    static_cast<Pass*>(self)->AddReduced(index, d, n);
  }

  const PointshellContactParams& params() const { return m.params_; }
  float Radius(int node) const { return m.shell_.Radius(node); }
  bool Asleep(int node) const {
    if constexpr (Shell::kDeforms) {  // the travel is >= 0: formed only for a node the clock alone keeps asleep
      return clock < m.wake_[node] &&
             clock + m.params_.lipschitz * double(m.shell_.Travel(node, m.sleep_stamp_[node])) < m.wake_[node];
    } else {
      return clock < m.wake_[node];
    }
  }
  void Sleep(int node, double margin) {
    m.wake_[node] = clock + margin;
    if constexpr (Shell::kDeforms) m.sleep_stamp_[node] = m.shell_.stamp();
  }
};

template <class Shell, class Field>
ContactResult PointshellFieldModel<Shell, Field>::Evaluate(const ContactQuery& query) {
  ContactResult result;
  contacts_.Clear();
  X_WB_contacts_ = query.X_WB;
  const BodyDeformation* def_A = query.deformation_A;
  const BodyDeformation* def_B = query.deformation_B;
  // This query's deformations (rigid sides take none).
  const bool fits_A = shell_.Begin(def_A ? def_A->q : nullptr);
  const bool fits_B = field_.Begin(def_B ? def_B->q : nullptr);
  if (!fits_A || !fits_B) {
    result.stats.faults = 1;
    return result;
  }
  const double clock = params_.lipschitz * double(query.cycle) * params_.max_point_speed * params_.cycle_seconds;

  // The reduced forces wanted of the deformable sides (an instance with none keeps no sums).
  struct NoSum {};
  [[maybe_unused]] std::conditional_t<Shell::kDeforms, ReducedForceSum, NoSum> sum_A;
  [[maybe_unused]] std::conditional_t<Field::kDeforms, ReducedForceSum, NoSum> sum_B;
  ReducedForceSum* want_A = nullptr;
  ReducedForceSum* want_B = nullptr;
  if constexpr (Shell::kDeforms) {
    if (def_A != nullptr && def_A->force != nullptr) {
      sum_A.Start(shell_.r(), def_A->stiffness != nullptr);
      want_A = &sum_A;
    }
  }
  if constexpr (Field::kDeforms) {
    if (def_B != nullptr && def_B->force != nullptr) {
      sum_B.Start(field_.r(), def_B->stiffness != nullptr);
      want_B = &sum_B;
    }
  }

  ContactAccumulator acc;
  FrictionSums friction;
  const Pointshell& s = shell_.shell();
  Pass pass{*this, s, FloatTransform(query.X_WB.Inverse() * query.X_WA), &acc, nullptr, want_A, want_B, clock};
  if constexpr (!kDeforms) {
    if (params_.friction.on()) {
      anchors_.BeginQuery();
      pass.friction = &friction;
      const int previous = traversal_.last_level_rendered();
      if (variant_ == Variant::kTree && previous >= 0 && previous < max_level_) {
        pass.inherit_begin = s.level_point_end[previous];
      }
    }
  }
  const bool halfspace = params_.gradient == ContactGradient::kHalfspace;
  HalfspaceContactBuffer contacts(pass.Points(), pass.X_BA, &acc,
                                  (want_A != nullptr || want_B != nullptr) ? &Pass::OnFlush : nullptr, &pass);
  if (halfspace) pass.contacts = &contacts;
  if (variant_ == Variant::kLinear) {
    RunLinearTraversal(s, max_level_, pass, &result.stats);
  } else {
    traversal_.Run(s, max_level_, params_, query.node_budget, pass, &result.stats);
  }
  contacts.Flush();
  acc.Finish(params_.penalty, query.X_WB, &result);
  if (pass.friction != nullptr) {
    FinishFriction(friction, params_.penalty, acc.count(), params_.friction, query.X_WB, &contacts_, &result);
  }

  // Force on A at a point: -k d N_A; on B: +k d N_B.
  if (want_A != nullptr || want_B != nullptr) {
    double scale = 1;
    const double k = params_.penalty.StiffnessFor(acc.count(), &scale);
    if (want_A != nullptr) want_A->Write(k, -1.0, def_A->force, def_A->stiffness);
    if (want_B != nullptr) want_B->Write(k, 1.0, def_B->force, def_B->stiffness);
  }
  return result;
}

template <class Shell, class Field>
int PointshellFieldModel<Shell, Field>::PointStates(const ContactQuery& query, std::span<const std::int32_t> points,
                                                    PointState* out) {
  if (variant_ == Variant::kTree) return traversal_.PointStates(points, out);
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);  // as Evaluate's
  const Pointshell& s = shell_.shell();
  return LinearPointStates(s, max_level_, points, out, [&](const std::int32_t* index, int n, float* d) {
    if constexpr (Shell::kDeforms) {  // the points at the latest query's q
      float px[kLinearPointStatesPerCall] = {}, py[kLinearPointStatesPerCall] = {}, pz[kLinearPointStatesPerCall] = {};
      shell_.Positions(index, 0, n, px, py, pz);
      field_.Distances(X_BA, px, py, pz, nullptr, n, d, nullptr);
    } else {
      field_.Distances(X_BA, s.x.data(), s.y.data(), s.z.data(), index, n, d, nullptr);
    }
  });
}

}  // namespace contactlab
