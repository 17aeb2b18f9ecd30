// Registers the VPS baseline with the contact-model registry (contact/model_registry.h):
//   "vps"            A's pointshell = centres of A's surface voxels at B's voxel size
//                    (BuildVpsPointshell), as McNeely et al. 1999 sample it, projected onto
//                    A's surface with the layered voxmap (as DLR's VPS samples it);
//   "vps-repulsion"  the scene's own pointshell of A (normally the paper's repulsion
//                    pointshell), to separate the force model from the sampling.
// Both take k_C, L, coherence, max_point_speed and cycle_seconds from the scene's model
// section, and their own key `voxmap` (vps_params.h: layered, the default, or surface); the
// voxel size is B's field spacing.
#include <memory>

#include "baselines/vps/vps_contact_model.h"
#include "baselines/vps/vps_params.h"
#include "baselines/vps/vps_pointshell.h"
#include "contact/model_registry.h"

namespace contactlab {
namespace {

VpsContactParams VpsParams(const ContactModelInputs& in) {
  const ContactParams& m = in.params;
  VpsContactParams p;
  p.voxmap = in.Params(VpsOwnParamTable()).voxmap;
  p.penalty = m.penalty;
  p.coherence = m.coherence;
  p.max_point_speed = m.max_point_speed;
  p.cycle_seconds = m.cycle_seconds;
  p.friction = m.friction;
  return p;
}

// "vps": A's pointshell of surface-voxel centres at B's voxel size; with the layered voxmap,
// projected onto A's surface as DLR's VPS samples it (the layered depth is B's true depth, so
// a centre half a voxel inside A would touch half a voxel late).
std::unique_ptr<ContactModel> MakeVps(const ContactModelInputs& in) {
  const VpsContactParams params = VpsParams(in);
  auto field_B = in.B.field();
  const double v = params.voxel_size > 0 ? params.voxel_size : field_B->spacing();
  Pointshell points = BuildVpsPointshell(*in.A.field(), v, in.A.sampling_seed());
  if (params.voxmap == VpsVoxmap::kLayered) ProjectVpsPointshellOntoSurface(*in.A.field(), &points);
  auto shell = std::make_shared<const Pointshell>(std::move(points));
  return std::make_unique<VpsContactModel>("vps", std::move(shell), std::move(field_B), params);
}

}  // namespace

void RegisterVpsContactModels() {
  RegisterContactModel({
      .name = "vps",
      .description = "Voxmap-PointShell (McNeely et al. 1999/2006, distance layers after DLR): voxel-centre pointshell",
      .needs = {.field_A = true, .field_B = true, .depth_in_field_voxels = true},
      .make = MakeVps,
      .friction = FrictionSupport::kRigidBodies,
      .pair_params = ParamBlock(VpsOwnParamTable()),
  });
  RegisterContactModel({
      .name = "vps-repulsion",
      .description = "VPS forces on the scene's own (repulsion) pointshell of A",
      .needs = {.pointshell_A = true, .field_B = true, .depth_in_field_voxels = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return std::make_unique<VpsContactModel>("vps-repulsion", in.A.pointshell(), in.B.field(), VpsParams(in));
      },
      .friction = FrictionSupport::kRigidBodies,
      .pair_params = ParamBlock(VpsOwnParamTable()),
  });
}

}  // namespace contactlab
