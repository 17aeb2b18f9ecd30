// The Bullet baseline's own keys in a scene's model section (register_bullet.cc): the collision
// margin, whether it is subtracted from the depths, and the collision shape of each body.
#pragma once

#include "util/param_table.h"

namespace contactlab {

// What Bullet collides (bullet_contact_model.h).
enum class BulletShape {
  kGImpact,              // btGImpactMeshShape of the triangle mesh: triangle-pair manifolds
  kConvexHull,           // btConvexHullShape of the mesh's vertices: one GJK/EPA point a query
  kConvexDecomposition,  // btGImpactConvexDecompositionShape: a compound of convex hulls
};

// The largest margin a scene may give (metres): 1 cm, a fifth of the smallest scene body.
constexpr double kMaxBulletMargin = 0.01;

struct BulletOwnParams {
  double margin = 0.0005;        // collision margin of each shape, metres (0.5 mm)
  bool subtract_margins = true;  // δ = -s - 2 margin (true) or δ = -s (false)
  BulletShape shape = BulletShape::kGImpact;  // what each mesh becomes
};

const ParamTable<BulletOwnParams>& BulletOwnParamTable();

}  // namespace contactlab
