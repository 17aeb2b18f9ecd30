// Friction shared by the contact models that carry it (docs/models.md, "Friction"): Coulomb's law
// on a stick anchor per contact, with no velocity estimate, so static virtual coupling works
// unchanged (the friction cone of the god-object methods, Salisbury et al. 1995 and Melder &
// Harwin 2003; the bristle of Hayward & Armstrong 2000).
//
// Each contact that a model can follow from cycle to cycle (a pointshell point: points are
// persistent) holds an anchor in B's frame, set where the contact first touched. The contact's
// tangential displacement u is the part of (contact point - anchor) in its tangent plane (normal
// N), and its tangential force on B is
//
//   F_t = kappa F_n u,   |u| <= mu / kappa,
//
// F_n the contact's normal force and kappa the tangential stiffness per newton of normal load
// (1/m). While |u| stays within mu_s / kappa the contact sticks; beyond it, the anchor is dragged
// so that |u| = mu_d / kappa and the contact slides, holding |F_t| = mu_d F_n. It slides on, at
// mu_d, while the anchor has to be dragged each cycle, and sticks again (at mu_s) in the first
// cycle it need not be: a tool that stops, or turns back, unloads elastically. Since the
// stiffness is proportional to the load, whether a contact sticks depends on its travel alone,
// and every contact of a patch slips at the same travel: a patch pressed with F_n reaches
// exactly mu_s F_n before it slips, whatever its distribution of pressure, and the same law
// gives the same force in every model that gives the same normal forces.
//
// The gradient (ContactResult::K_B, contact_model.h's convention) of each contact's friction
// wrench, under a perturbation of B's pose with the anchors held: the anchor moves with B, the
// contact point and normal stay with A, and F_n changes with the depth (g: the depth's gradient).
// With r the anchor and q the contact point (both relative to B's origin), c = kappa F_n and
// Q = I - N N^T for a sticking contact, I - N N^T - u u^T / |u|^2 for a sliding one (the rim's
// tangent):
//
//   dF/dx     = kappa k u g^T - c Q           dF/dtheta = kappa k u (q x g)^T + c Q [r]x
//   dT/dx     = [F]x + [q]x dF/dx             dT/dtheta = [q]x dF/dtheta
//
// (k: the normal force per metre of depth, F_n = k |d|). Everything here runs in the haptic
// cycle: the anchors sit in flat arrays sized when the model is built; nothing allocates or
// throws.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_model.h"
#include "contact/contact_recorder.h"
#include "contact/penalty_params.h"
#include "geometry/pose.h"
#include "util/param_table.h"

namespace contactlab {

struct FrictionParams {
  static constexpr double kDefaultTangentialStiffness = 1000;  // kappa, 1/m
  // A sliding contact's travel mu_d / kappa below this (metres) slides without friction: a rim
  // of less than a picometre is no rim, and its inverse square would overflow the gradient's sums.
  static constexpr double kSmallestRim = 1e-12;

  double mu_static = 0;   // mu_s; 0: no friction (the default)
  double mu_dynamic = 0;  // mu_d <= mu_s
  double tangential_stiffness = kDefaultTangentialStiffness;  // kappa: N/m of tangential stiffness per N of load
  double match_radius = 1e-3;  // m: models whose contacts are new each query match them this far (friction_matching.h)
  bool on() const { return mu_static > 0; }
  // mu_d / kappa, the travel of a sliding contact; 0 below kSmallestRim.
  double rim() const {
    const double r = mu_dynamic / tangential_stiffness;
    return r >= kSmallestRim ? r : 0.0;
  }
};

// The `friction:` block of a scene's model section (and of a pair's).
const ParamTable<FrictionParams>& FrictionParamTable();

// Which bodies a model carries friction between (ContactModelEntry::friction).
enum class FrictionSupport {
  kNone,         // frictionless only: a scene that asks for friction is refused
  kRigidBodies,  // between rigid bodies; refused when either deforms
};

// Coulomb's law on one anchor (the top of this file): the contact at P (B's frame) with unit
// normal N, its anchor *ANCHOR (B's frame) and whether it slid the query before (SLID_BEFORE):
// drags *ANCHOR onto the rim when the contact slips, sets *SLIDING when it did, and returns
// the tangential displacement u after that.
inline Eigen::Vector3d ApplyCoulomb(const Eigen::Vector3d& p, const Eigen::Vector3d& n, const FrictionParams& f,
                                    bool slid_before, Eigen::Vector3d* anchor, bool* sliding) {
  const Eigen::Vector3d delta = p - *anchor;
  const double along_n = delta.dot(n);
  Eigen::Vector3d u = delta - along_n * n;
  const double travel2 = u.squaredNorm();
  const double limit = (slid_before ? f.mu_dynamic : f.mu_static) / f.tangential_stiffness;
  *sliding = travel2 > limit * limit;
  if (*sliding) {
    u *= f.rim() / std::sqrt(travel2);
    *anchor = p - u - along_n * n;
  }
  return u;
}

// The anchors of up to N contacts, indexed by the model's own contact index (a pointshell's
// point index).
class FrictionAnchors {
 public:
  FrictionAnchors() = default;
  // Room for N contacts, all without anchor. Allocates; call when the model is built.
  explicit FrictionAnchors(int n) : slots_(std::size_t(n)) {}

  // At the start of each query: the anchors of contacts the previous query saw stay alive.
  void BeginQuery() {
    if (++epoch_ == ~0u) {  // the stamp would wrap: start over, every anchor gone
      for (Slot& s : slots_) s.stamp = 0;
      epoch_ = 2;
    }
  }
  // Forgets every anchor.
  void Reset() {
    BeginQuery();
    BeginQuery();
  }
  // True when contact I has an anchor carried over from the previous query or set in this one.
  bool Alive(int i) const { return slots_[std::size_t(i)].stamp + 1 >= epoch_; }
  // Contact I's anchor (B's frame), for a contact whose anchor is alive.
  const Eigen::Vector3d& anchor(int i) const { return slots_[std::size_t(i)].anchor; }

  // Contact I at point P (B's frame) with unit normal N, this query: sets its anchor at first
  // touch (at P - INHERIT, INHERIT a displacement it takes over from a coarser contact; zero for
  // none), drags it onto the rim when the contact slips, and returns the tangential displacement
  // u after that, with *SLIDING set when the anchor was dragged.
  Eigen::Vector3d Update(int i, const Eigen::Vector3d& p, const Eigen::Vector3d& n, const Eigen::Vector3d& inherit,
                         const FrictionParams& f, bool* sliding) {
    Slot& s = slots_[std::size_t(i)];
    if (s.stamp + 1 < epoch_) {  // no anchor alive
      s.anchor = p - inherit;
      s.sliding = 0;
    }
    s.stamp = epoch_;
    const Eigen::Vector3d u = ApplyCoulomb(p, n, f, s.sliding != 0, &s.anchor, sliding);
    s.sliding = *sliding ? 1 : 0;
    return u;
  }

 private:
  // One contact's anchor (B's frame, metres), the epoch_ of the query that last saw it (0:
  // never) and whether it slid then: one cache line's half, read and written together.
  struct Slot {
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    std::uint32_t stamp = 0;
    std::uint8_t sliding = 0;
  };
  std::vector<Slot> slots_;  // (#contacts)
  std::uint32_t epoch_ = 2;
};

// The per-contact terms FrictionSums keeps until a flush (SoA floats, friction_sums.cc): load
// weight w, z = w / |u|^2 for a sliding contact (0 for a sticking one), displacement u, normal
// N, depth gradient g, point q and anchor r, in B's frame; kPadding lanes past the last.
struct FrictionBatch {
  static constexpr int kSize = 256;
  static constexpr int kPadding = 64;  // HWY_MAX_BYTES / sizeof(float): one vector of any target
  float w[kSize + kPadding], z[kSize + kPadding];
  float u[3][kSize + kPadding], N[3][kSize + kPadding], g[3][kSize + kPadding];
  float q[3][kSize + kPadding], r[3][kSize + kPadding];
};
// The kernel's sums (per unit of kappa k), in its five passes (friction_sums.cc).
struct FrictionBatchTotals {
  double pass1[25] = {};  // w u, w q x u, u g^T, w N N^T (upper), sum w, sum w r
  double pass2[22] = {};  // z u u^T, sum w q, sum w q . r, u (q x g)^T
  double pass3[27] = {};  // w N (N x r)^T, z u (u x r)^T, (q x u) g^T
  double pass4[27] = {};  // w (q x N) N^T, z (q x u) u^T, (q x u)(q x g)^T
  double pass5[27] = {};  // w r q^T, w (q x N)(N x r)^T, z (q x u)(u x r)^T
};

// Sums the friction wrench of one query's contacts and its gradient in B's frame (see the top
// of this file), kept a batch at a time and summed by a vectorised kernel (Google Highway, the
// instruction set chosen at run time, friction_sums.cc); Finish turns them into the world frame.
class FrictionSums {
 public:
  // A contact at point Q (B's frame, relative to B's origin) with unit normal N, depth weight W
  // = |d| (its normal force is k W), depth gradient G, anchor R, tangential displacement U and
  // SLIDING as FrictionAnchors::Update returned, under law F (a sliding contact's |u| is its
  // rim's, mu_d / kappa).
  void Add(const Eigen::Vector3d& q, const Eigen::Vector3d& n, double w, const Eigen::Vector3d& g,
           const Eigen::Vector3d& r, const Eigen::Vector3d& u, bool sliding, const FrictionParams& f) {
    const int k = count_;
    batch_.w[k] = float(w);
    // w / |u|^2 for a sliding contact: |u| is the rim's (0 for a rim below kSmallestRim, whose u
    // is 0).
    const double rim = sliding ? f.rim() : 0.0;
    batch_.z[k] = rim > 0 ? float(w / (rim * rim)) : 0.f;
    for (int a = 0; a < 3; ++a) {
      batch_.u[a][k] = float(u[a]), batch_.N[a][k] = float(n[a]), batch_.g[a][k] = float(g[a]);
      batch_.q[a][k] = float(q[a]), batch_.r[a][k] = float(r[a]);
    }
    if (sliding) ++sliding_;
    if (++count_ == FrictionBatch::kSize) Flush();
  }

  // Counts each contact added so far F times (a budget that looked at one contact in F stands
  // for the whole, as ContactAccumulator::Scale).
  void Scale(double f) {
    scale_ *= f;
    sliding_ = int(std::lround(sliding_ * f));
  }

  int sliding() const { return sliding_; }
  // Forgets every contact added (for sums reused from query to query).
  void Clear() {
    count_ = 0;
    totals_ = {};
    scale_ = 1;
    sliding_ = 0;
  }

  // Adds the friction wrench and its gradient to OUT (world frame, torque about B's origin) for
  // normal stiffness K (N/m of depth, after any scaling) and tangential stiffness KAPPA, B at
  // X_WB.
  void Finish(double k, double kappa, const Pose& X_WB, ContactResult* out) {
    Flush();
    const FrictionBatchTotals& t = totals_;
    auto M = [](const double* v) { return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v); };
    auto V = [](const double* v) { return Eigen::Vector3d(v[0], v[1], v[2]); };
    const double* s = t.pass1 + 15;
    Eigen::Matrix3d wNN;
    wNN << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const double sw = t.pass1[21], swqr = t.pass2[12];
    const double c = k * kappa * scale_;
    Matrix6d K;
    K.block<3, 3>(0, 0) = M(t.pass1 + 6) - sw * I + wNN + M(t.pass2);
    K.block<3, 3>(0, 3) = M(t.pass2 + 13) + ContactAccumulator::Skew(V(t.pass1 + 22)) - M(t.pass3) - M(t.pass3 + 9);
    K.block<3, 3>(3, 0) = M(t.pass3 + 18) - ContactAccumulator::Skew(V(t.pass2 + 9)) + M(t.pass4) + M(t.pass4 + 9);
    K.block<3, 3>(3, 3) = M(t.pass4 + 18) + M(t.pass5) - swqr * I - M(t.pass5 + 9) - M(t.pass5 + 18);
    const Eigen::Vector3d F_B = c * V(t.pass1);
    Matrix6d K_B = c * K;
    K_B.block<3, 3>(3, 0) += ContactAccumulator::Skew(F_B);
    const Eigen::Matrix3d R = X_WB.R();
    out->on_B.force += R * F_B;
    out->on_B.torque += R * (c * V(t.pass1 + 3));
    Matrix6d Rb = Matrix6d::Zero();
    Rb.block<3, 3>(0, 0) = R;
    Rb.block<3, 3>(3, 3) = R;
    out->K_B += Rb * K_B * Rb.transpose();
  }

 private:
  // Sums the batch into totals_ and empties it (friction_sums.cc).
  void Flush();

  FrictionBatch batch_;
  int count_ = 0;  // contacts in batch_
  FrictionBatchTotals totals_;
  double scale_ = 1;
  int sliding_ = 0;  // contacts that slid, counted as Scale counts them
};

// One contact of a query with friction on: its anchor's update (FrictionAnchors::Update) and its
// terms added to SUMS (FrictionSums::Add), returning its displacement after the update in *U and
// whether it slid. Contact I at point P (B's frame) with unit normal N, depth weight W, depth
// gradient G; INHERIT as Update's.
inline bool AddFrictionContact(FrictionAnchors* anchors, FrictionSums* sums, const FrictionParams& f, int i,
                               const Eigen::Vector3d& p, const Eigen::Vector3d& n, double w, const Eigen::Vector3d& g,
                               Eigen::Vector3d* u, const Eigen::Vector3d& inherit = Eigen::Vector3d::Zero()) {
  bool sliding = false;
  *u = anchors->Update(i, p, n, inherit, f, &sliding);
  sums->Add(p, n, w, g, anchors->anchor(i), *u, sliding, f);
  return sliding;
}

// The end of a penalty model's query with friction on: SUMS added to OUT with the normal
// stiffness PENALTY gives COUNT contacts (after its L / l scaling), the sliding contacts counted
// in OUT's stats, and CONTACTS (when kept) told the factor of their friction forces.
inline void FinishFriction(FrictionSums& sums, const PenaltyParams& penalty, int count, const FrictionParams& f,
                           const Pose& X_WB, ContactRecorder* contacts, ContactResult* out) {
  const double k = penalty.StiffnessFor(count);
  sums.Finish(k, f.tangential_stiffness, X_WB, out);
  out->stats.contacts_sliding = sums.sliding();
  contacts->ScaleTangential(k * f.tangential_stiffness);
}

}  // namespace contactlab
