#include "baselines/bullet/bullet_params.h"

#include <string>
#include <utility>
#include <vector>

namespace contactlab {

const ParamTable<BulletOwnParams>& BulletOwnParamTable() {
  using P = ParamRows<BulletOwnParams>;
  static const ParamTable<BulletOwnParams> table(
      "bullet", "The Bullet baseline (bullet): its collision margin and body shapes.",
      {
          P::Number("bullet_margin", PARAM_MEMBER(margin), AtLeast(0), AtMost(kMaxBulletMargin),
                    "bullet: collision margin of each body's shape; Bullet thickens every triangle (or hull) "
                    "by it, so touching surfaces already report a depth of 2 margins. Up to 1 cm")
              .Unit("m").Sweepable().Example("0.0001"),
          P::Boolean("bullet_subtract_margins", PARAM_MEMBER(subtract_margins),
                     "bullet: subtract both margins from each manifold point's depth (true: contact starts "
                     "where the meshes touch; false: 2 margins earlier, at the thickened shapes)")
              .Sweepable().Example("false"),
          P::Mapped("bullet_shape", PARAM_MEMBER(shape),
                    std::vector<std::pair<std::string, BulletShape>>{
                        {"gimpact", BulletShape::kGImpact},
                        {"convex-hull", BulletShape::kConvexHull},
                        {"convex-decomposition", BulletShape::kConvexDecomposition}},
                    "bullet: collision shape of each body. gimpact: btGImpactMeshShape of the triangle mesh, "
                    "manifold points of triangle pairs; convex-hull: btConvexHullShape of the mesh's vertices, "
                    "one GJK/EPA point with the hulls' penetration depth (sensible for convex bodies only); "
                    "convex-decomposition: btGImpactConvexDecompositionShape (libbullet-extras' GIMPACTUtils "
                    "with Ratcliff's ConvexDecomposition), a compound of convex hulls built at construction, "
                    "one GJK/EPA point per overlapping pair of pieces")
              .Sweepable().Example("convex-hull"),
      });
  return table;
}

}  // namespace contactlab
