// The common contact interface (docs/architecture.md, "The contact interface"): every model —
// the paper's pointshell-vs-field model and each baseline — answers one query per haptic cycle
// through it.
//
// Conventions. Body A is the pointshell (or first) body, B the distance-field (or second)
// body. The result is the wrench ON B, torque about B's origin, world frame, SI units. Its
// gradient K_B is d(wrench on B)/d(pose of B) for the perturbation X_WB -> (exp([dθ]) R_WB,
// p_WB + dx) with dx, dθ in world coordinates, ordered (dx, dθ) and (force, torque).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "reduced/reduced_state.h"
#include "geometry/pose.h"

namespace contactlab {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // newtons
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // newton metres
  Vector6d AsVector() const {
    Vector6d v;
    v << force, torque;
    return v;
  }
};

struct ContactStats {
  std::int32_t points_in_contact = 0;  // points (or contacts) contributing force
  std::int64_t nodes_visited = 0;      // tree nodes / points / primitives examined
  std::int32_t level_rendered = -1;    // deepest tree level completed (-1: not a tree model)
  std::int32_t nodes_skipped_coherence = 0;
  double max_penetration = 0;          // largest |d| over contributing points, metres
  double stiffness_scale = 1;          // L / l when l >= L points touch, else 1
  // Volumetric models (pressure-field): the contact surface's area (m^2) and its connected
  // pieces; 0 for models without a contact surface.
  double contact_area = 0;
  std::int32_t patches = 0;
  // 1 when the model refused the query and gave no force: a deformation whose size does not
  // fit its body. The haptic cycle and the runners count it as a fault.
  std::int32_t faults = 0;
  // How far the query's work budget (ContactQuery::node_budget) made the model degrade: 0 when
  // it did all its work; else the steps it fell short by, in the model's own documented unit
  // (the paper's model: tree levels left out; pressure-field: doublings of its lattice; vps:
  // halvings of the share of points tested; inner-spheres: levels of the pair tree left out;
  // pointshell-ccd: 1, a search stopped and the proxy with it).
  std::int32_t degraded = 0;
  // Wall time within the query spent stepping deformable bodies the model advances itself (a
  // world of many bodies steps each of its deformable bodies once per cycle), ns; 0 otherwise.
  std::int64_t step_ns = 0;
  // Friction (contact/friction.h): contacts whose anchor slid in this query; 0 when friction
  // is off. Those in contact less these stick.
  std::int32_t contacts_sliding = 0;
};

struct ContactQuery {
  Pose X_WA;                            // world pose of body A
  Pose X_WB;                            // world pose of body B
  // A deformable body's reduced coordinates in, its reduced contact force out (models that
  // render its deformation: ContactModelNeeds::deformable_A / _B). Null: rigid, or at rest
  // with nothing wanted.
  const BodyDeformation* deformation_A = nullptr;
  const BodyDeformation* deformation_B = nullptr;
  std::int64_t cycle = 0;               // haptic cycle index, for temporal coherence
  std::int64_t node_budget = 0;         // graceful degradation; <= 0 means unlimited
};

struct ContactResult {
  Wrench on_B;
  Matrix6d K_B = Matrix6d::Zero();
  ContactStats stats;
};

// A contact surface for display: triangles, three world corners each (metres), and the
// pressure at each corner (Pa).
struct ContactSurface {
  std::vector<Eigen::Vector3f> corners;
  std::vector<float> pressure;
};

// The contacts a model used in one query, one entry per contact, world frame, SI units
// (ContactModel::KeepContacts / LatestContacts). Entry i: POINTS[i] (metres), NORMALS[i] the
// unit direction of the force on B at that contact, DEPTHS[i] its penetration depth (metres,
// >= 0). A model whose contacts are pieces of a surface (pressure-field) also fills AREAS[i]
// (m^2) and PRESSURES[i] (mean pressure over the piece, Pa); the others leave both empty. With
// friction on (contact/friction.h), TANGENTIAL[i] is the contact's friction force on B (N) and
// STICKING[i] 1 while it sticks, 0 when it slid; both empty with friction off. What a model's
// contacts are is documented beside the model and in docs/models.md.
struct ContactList {
  std::vector<Eigen::Vector3d> points;   // (N) world frame, metres
  std::vector<Eigen::Vector3d> normals;  // (N) world frame, unit: direction of the force on B
  std::vector<double> depths;            // (N) metres, >= 0
  std::vector<double> areas;             // (N) m^2, or empty
  std::vector<double> pressures;         // (N) Pa, or empty
  std::vector<Eigen::Vector3d> tangential;  // (N) world frame, newtons, or empty: friction force on B
  std::vector<std::uint8_t> sticking;       // (N) 1: sticks, 0: slid, or empty
  // Contacts the model used that did not fit the room KeepContacts reserved (not listed).
  std::int64_t not_kept = 0;
  int size() const { return int(points.size()); }
  void Clear() {
    points.clear(), normals.clear(), depths.clear(), areas.clear(), pressures.clear();
    tangential.clear(), sticking.clear();
    not_kept = 0;
  }
};

// What one pointshell point did in a model's latest query (for display, as the paper's Fig. 2).
enum class PointState : std::uint8_t {
  kNotEvaluated = 0,  // culled with its subtree, asleep under coherence, or below the level rendered
  kClear = 1,         // evaluated, d >= 0
  kInContact = 2,     // evaluated, d < 0: carries force
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::string_view name() const = 0;
  // One haptic cycle. Implementations allocate nothing and throw nothing here.
  virtual ContactResult Evaluate(const ContactQuery& query) = 0;
  // Forgets temporal state (coherence, level-of-detail hysteresis).
  virtual void Reset() = 0;
  // The caller saw the bodies move faster than the scene's max_point_speed, which temporal
  // coherence trusts (haptic cycle and runner, contact/coherence_guard.h): forgets what
  // coherence assumed. By default all temporal state (Reset); a model whose state is no such
  // shortcut keeps it (pointshell-ccd's proxy: its search holds at any speed, and forgetting it
  // would let B jump through A).
  virtual void ResetCoherence() { Reset(); }
  // For display: the states of body A's pointshell points POINTS (indices into the shell the
  // model traverses) in the latest Evaluate, whose query was QUERY, written to OUT[0..k).
  // Returns k, how many leading points were written: fewer than asked when a model bounds its
  // work per call (it then re-evaluates distances), 0 when it has no pointshell. Call it after
  // Evaluate and before the query's deformations change. Allocation-free, throws nothing.
  virtual int PointStates(const ContactQuery& query, std::span<const std::int32_t> points, PointState* out) {
    (void)query, (void)points, (void)out;
    return 0;
  }
  // A model that keeps a proxy of B between cycles (pointshell-ccd: B's pose held back where it
  // first touches A) writes the proxy's world pose after the latest Evaluate to *X_WB_PROXY and
  // returns true; the others return false. For display and tests; throws nothing.
  virtual bool Proxy(Pose* X_WB_proxy) const {
    (void)X_WB_proxy;
    return false;
  }
  // For display: a model whose contact is a surface (pressure-field) keeps up to MAX_TRIANGLES
  // triangles of the contact surface of every later Evaluate (0: none) and returns true; the
  // others return false. Call it outside the haptic cycle: it reserves the memory.
  virtual bool KeepContactSurface(int max_triangles) {
    (void)max_triangles;
    return false;
  }
  // The surface kept of the latest Evaluate, in the world, replacing OUT's contents; empty when
  // the model keeps none. For display, not for the haptic cycle: it may allocate.
  virtual void LatestContactSurface(ContactSurface* out) const {
    out->corners.clear();
    out->pressure.clear();
  }
  // A model with discrete contacts (ContactList) keeps up to MAX_CONTACTS of them in every
  // later Evaluate (0: none) and returns true; a model without any (a volume integral, a
  // proxy spring with no contact set) returns false. Call it outside the haptic cycle: it
  // reserves the memory, so that Evaluate still allocates nothing; contacts past MAX_CONTACTS
  // are counted (ContactList::not_kept), not kept.
  virtual bool KeepContacts(int max_contacts) {
    (void)max_contacts;
    return false;
  }
  // The contacts kept of the latest Evaluate, world frame, replacing OUT's contents; empty
  // when the model keeps none (or KeepContacts was not called before that Evaluate). Not for
  // the haptic cycle: it may allocate.
  virtual void LatestContacts(ContactList* out) const { out->Clear(); }
};

}  // namespace contactlab
