// Baseline: Bullet (3.24, double precision) GImpact mesh-mesh contact manifolds turned into
// penalty wrenches, for comparison with the paper's model (Barbič & James 2008, sec. 2.1, 5).
//
// Both meshes become btGImpactMeshShape (over btTriangleIndexVertexArray views of our own
// vertex and index copies, bounds updated once) with an explicit collision margin; a query
// sets the two objects' world transforms and calls btCollisionWorld::contactPairTest. That
// function looks up the dispatcher's *closest-points* table, which has no GImpact entry by
// default (so it returns nothing, bullet3 issue #1534): the constructor registers GImpact's
// algorithm there too (registerClosestPointsCreateFunc), besides the usual
// btGImpactCollisionAlgorithm::registerAlgorithm.
//
// Each manifold point (distance s < 0 when penetrating, unit normal n on B pointing from B
// toward A — Bullet's m_normalWorldOnB convention, checked by a unit test) is a penalty
// contact with depth δ = -s - (margin_A + margin_B) when subtract_margins (GImpact thickens
// every triangle by its shape's margin, so touching surfaces already report s = -2 margin):
//     force on B  = -k δ n at the midpoint of the manifold points on A and B (pushes B away)
//     torque      = (p - p_WB) × force (about B's origin)
//     gradient    = the paper's halfspace rule with N = n: dF/dx_B = -k n nᵀ, ...
// summed by ContactAccumulator with k = k_C, scaled to k_C L / l when l >= L contacts touch.
//
// Contacts (KeepContacts / LatestContacts): Bullet's manifold points with δ > 0 (as many as
// stats.points_in_contact): the midpoint p above (world), the direction of the force on B, -n,
// and the depth δ (margins subtracted when subtract_margins).
//
// Settings (bullet_params.h, the scene's model keys bullet_margin, bullet_subtract_margins,
// bullet_shape): the margin and whether it is subtracted, and the shape each mesh becomes:
// btGImpactMeshShape (default, as above), btConvexHullShape of its vertices (Bullet's
// convex-convex algorithm, GJK with EPA: one point with the hulls' penetration depth, for
// convex bodies), or btGImpactConvexDecompositionShape (libbullet-extras' GIMPACTUtils: the
// mesh cut into convex hulls by Ratcliff's ConvexDecomposition at construction, GImpact's
// compound traversal, one GJK/EPA point per overlapping pair of pieces).
//
// Caveats (baselines/README.md): GImpact's triangle-pair clipping reports up to 16 points per
// overlapping triangle pair with a depth local to that pair; the contact count follows the
// tessellation, and deep or thin overlaps give arbitrary normals.
#pragma once

#include <cstdint>
#include <memory>

#include "baselines/bullet/bullet_params.h"
#include "contact/contact_model.h"
#include "contact/friction.h"
#include "contact/penalty_params.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

// Friction (contact/friction.h, params.friction): contactPairTest keeps no persistent manifold
// between calls, so the manifold points are matched to the previous query's by their position
// on A (contact/friction_matching.h, Bullet's own getCacheEntry rule: the nearest point within a
// radius); each point's load weight is its δ, its gradient the halfspace rule's N.
struct BulletContactParams {
  PenaltyParams penalty;  // k_C per contact and the L / l scaling, as the paper's model
  BulletOwnParams own;    // margin, its subtraction and each mesh's shape (bullet_params.h)
  FrictionParams friction;  // off by default
};

class BulletContactModel final : public ContactModel {
 public:
  // MESH_A, MESH_B in their body frames (metres). Throws Error for an empty mesh, invalid
  // indices, a negative margin or a negative / non-finite k_C.
  BulletContactModel(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                     const BulletContactParams& params);
  ~BulletContactModel() override;

  std::string_view name() const override { return "bullet"; }
  // stats: points_in_contact = manifold points with δ > 0, nodes_visited = all manifold
  // points Bullet reported, max_penetration = largest δ. Throws nothing. Our side allocates
  // nothing (points are summed as the callback sees them, no buffer); Bullet itself takes the
  // algorithm and the manifold from its pool allocators and heap-allocates the overlapping
  // triangle-pair list (btPairSet, a btAlignedObjectArray local to
  // btGImpactCollisionAlgorithm::gimpact_vs_gimpact) on every query. The convex-hull shape's
  // query allocates nothing beyond the pools; the convex decomposition's allocates like GImpact's.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override;
  // The manifold points with δ > 0 (see the top of this file), recorded during Evaluate.
  bool KeepContacts(int max_contacts) override;
  void LatestContacts(ContactList* out) const override;

  const BulletContactParams& params() const { return params_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  BulletContactParams params_;
};

}  // namespace contactlab
