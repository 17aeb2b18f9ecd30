#include "baselines/fcl/fcl_params.h"

#include <string>
#include <utility>
#include <vector>

namespace contactlab {
namespace {

const std::vector<std::pair<std::string, FclBv>>& BvNames() {
  static const std::vector<std::pair<std::string, FclBv>> names{
      {"obbrss", FclBv::kObbrss}, {"obb", FclBv::kObb}, {"kios", FclBv::kKios}};
  return names;
}

}  // namespace

const char* FclBvName(FclBv bv) {
  for (const auto& [name, value] : BvNames()) {
    if (value == bv) return name.c_str();
  }
  return "?";
}

const ParamTable<FclOwnParams>& FclOwnParamTable() {
  using P = ParamRows<FclOwnParams>;
  static const ParamTable<FclOwnParams> table(
      "fcl", "The FCL baseline (fcl): its bounding volumes, contact cap and body shapes.",
      {
          P::Mapped("fcl_bv", PARAM_MEMBER(bv), BvNames(),
                    "fcl: bounding volume of the mesh hierarchies (BVHModel), each traversed with the bodies' "
                    "transforms applied on the fly. Every type gives the same contacts (the same triangle pairs "
                    "are tested). FCL's other types (rss, aabb, the k-DOPs) are not offered: FCL 0.7 collides "
                    "them by copying both hierarchies every query, and that copy frees with delete[] what it "
                    "took from malloc (fcl_params.h). Applies to fcl_shape: mesh")
              .Sweepable().Example("kios"),
          P::Integer("fcl_max_contacts", PARAM_MEMBER(max_contacts), 1, 100000000,
                     "fcl: FCL's num_max_contacts, the most contacts one query reports (FCL stops its "
                     "traversal there, so a small cap keeps the first triangle pairs found, not the deepest)")
              .Sweepable().Example("64"),
          P::Mapped("fcl_shape", PARAM_MEMBER(shape),
                    std::vector<std::pair<std::string, FclShape>>{{"mesh", FclShape::kMesh},
                                                                  {"convex", FclShape::kConvex}},
                    "fcl: what FCL collides. mesh: each body's triangle mesh, contacts of triangle pairs with "
                    "a depth local to the pair; convex: fcl::Convex of each mesh's vertices, i.e. their "
                    "convex hull, one contact with the hulls' penetration depth by libccd's MPR, FCL's default "
                    "(sensible for convex bodies only: a concave body collides as its hull)")
              .Sweepable().Example("convex"),
      });
  return table;
}

}  // namespace contactlab
