// The VPS baseline's own key in a scene's model section: which voxmap force model it renders,
// the distance-layered one (default) or McNeely et al.'s 1999 surface layer. Carried by both
// registry entries ("vps", "vps-repulsion"; register_vps.cc).
#pragma once

#include "util/param_table.h"

namespace contactlab {

// What a point in a contact voxel feels (vps_contact_model.h).
enum class VpsVoxmap {
  kLayered,  // depth of the voxel centre in layers plus the offset along B's normal there
  kSurface,  // McNeely et al. 1999: tangent plane through a surface voxel's centre, fixed interior depth
};

struct VpsOwnParams {
  VpsVoxmap voxmap = VpsVoxmap::kLayered;
};

const ParamTable<VpsOwnParams>& VpsOwnParamTable();

}  // namespace contactlab
