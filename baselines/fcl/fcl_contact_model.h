// Baseline: FCL (Flexible Collision Library 0.7) mesh-mesh contacts turned into penalty
// wrenches, for comparison with the paper's model (Barbič & James 2008, sec. 2.1 and 5).
//
// Both meshes become BVHModel<OBBRSS> once, at construction; a query only sets the two
// objects' transforms (OBBRSS traversal applies them on the fly, nothing is copied) and calls
// fcl::collide with contacts enabled. Each contact (position p, unit normal n pointing from
// object 1 = A to object 2 = B — FCL's convention, checked by a unit test — and penetration
// depth δ > 0) is a penalty contact:
//     force on B  = k δ n  at p        (pushes B away from A)
//     torque      = (p - p_WB) × force (about B's origin)
//     gradient    = the paper's halfspace rule with N = -n: dF/dx_B = -k n nᵀ, ...
// summed by ContactAccumulator (contact/contact_accumulator.h) with the paper's stiffness
// k = k_C, scaled to k_C L / l when l >= L contacts touch, so magnitudes are comparable.
//
// Contacts (KeepContacts / LatestContacts): FCL's own, one per contact with δ > 0 (as many as
// stats.points_in_contact): its position p (world), its normal n (the direction of the force
// on B) and its penetration depth δ.
//
// Settings (fcl_params.h, the scene's model keys fcl_bv, fcl_max_contacts, fcl_shape): the
// hierarchies' bounding volume (OBBRSS by default; every type gives the same contacts), FCL's
// contact cap, and fcl_shape: convex, which collides fcl::Convex of each mesh's vertices (their
// convex hull) instead: one contact whose depth is the hulls' penetration depth by libccd's MPR
// (FCL's default solver; why not FCL's own GJK/EPA: fcl_params.h).
//
// Caveats (see baselines/README.md): FCL's mesh-mesh penetration depth is local to one
// triangle pair, not the depth of the bodies' overlap, and its normal is a triangle's normal
// whose sign depends on the winding (FCL issues #574 and #8); the number of contacts depends
// on the tessellation, not on the contact area.
#pragma once

#include <cstddef>
#include <memory>

#include "baselines/fcl/fcl_params.h"
#include "contact/contact_model.h"
#include "contact/friction.h"
#include "contact/penalty_params.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

// Friction (contact/friction.h, params.friction): FCL's contacts are new every query, so they are
// matched to the previous query's by their position on A (contact/friction_matching.h); each
// contact's load weight is its δ, its gradient the halfspace rule's N, as its normal force.
struct FclContactParams {
  PenaltyParams penalty;  // k_C per contact and the L / l scaling, as the paper's model
  FclOwnParams own;       // bounding volume, contact cap and each body's shape (fcl_params.h)
  FrictionParams friction;  // off by default
};

class FclContactModel final : public ContactModel {
 public:
  // MESH_A, MESH_B: closed or not, in their body frames (metres). Throws Error for an empty
  // mesh, invalid triangle indices, max_contacts 0 or a negative / non-finite k_C.
  FclContactModel(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                  const FclContactParams& params);
  ~FclContactModel() override;

  std::string_view name() const override { return "fcl"; }
  // stats: points_in_contact = contacts with δ > 0, nodes_visited = all FCL contacts,
  // max_penetration = largest δ. Throws nothing. FCL keeps its contact vector between calls
  // (cleared, capacity kept), so after the first deep query it does not allocate for
  // contacts; its traversal allocates nothing for OBBRSS, OBB and kIOS (the bounding volumes
  // offered, fcl_params.h). With fcl_shape: convex, libccd's support function allocates a
  // visited-vertex list per call (Convex::findExtremeVertex).
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // FCL's contacts with δ > 0 (see the top of this file), recorded during Evaluate.
  bool KeepContacts(int max_contacts) override;
  void LatestContacts(ContactList* out) const override;

  const FclContactParams& params() const { return params_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  FclContactParams params_;
};

}  // namespace contactlab
