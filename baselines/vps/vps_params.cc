#include "baselines/vps/vps_params.h"

namespace contactlab {

const ParamTable<VpsOwnParams>& VpsOwnParamTable() {
  using P = ParamRows<VpsOwnParams>;
  static const ParamTable<VpsOwnParams> table(
      "vps", "The Voxmap-PointShell baseline (vps, vps-repulsion): its voxmap force model.",
      {
          P::Mapped("voxmap", PARAM_MEMBER(voxmap),
                    std::vector<std::pair<std::string, VpsVoxmap>>{{"layered", VpsVoxmap::kLayered},
                                                                   {"surface", VpsVoxmap::kSurface}},
                    "vps: force model of the voxmap. layered: every surface and interior voxel carries its "
                    "centre's depth in voxel layers and B's normal there (DLR's VPS), so the force grows with "
                    "depth through the interior; surface: McNeely et al. 1999, the tangent plane through a "
                    "surface voxel's centre and a fixed half-diagonal depth in the interior")
              .Sweepable().Example("surface"),
      });
  return table;
}

}  // namespace contactlab
