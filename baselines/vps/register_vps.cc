// Registers the VPS baseline with the contact-model registry (contact/model_registry.h):
//   "vps"            A's pointshell = centres of A's surface voxels at B's voxel size
//                    (BuildVpsPointshell), as McNeely et al. 1999 sample it;
//   "vps-repulsion"  the scene's own pointshell of A (normally the paper's repulsion
//                    pointshell), to separate the force model from the sampling.
// Both take k_C, L, coherence, max_point_speed and cycle_seconds from the scene's model
// section; the voxel size is B's field spacing.
#include <memory>

#include "baselines/vps/vps_contact_model.h"
#include "baselines/vps/vps_pointshell.h"
#include "contact/model_registry.h"

namespace contactlab {
namespace {

VpsContactParams VpsParams(const ContactParams& m) {
  VpsContactParams p;
  p.penalty = m.penalty;
  p.coherence = m.coherence;
  p.max_point_speed = m.max_point_speed;
  p.cycle_seconds = m.cycle_seconds;
  return p;
}

// "vps": A's pointshell of surface-voxel centres at B's voxel size.
std::unique_ptr<ContactModel> MakeVps(const ContactModelInputs& in) {
  const VpsContactParams params = VpsParams(in.params);
  auto field_B = in.B.field();
  const double v = params.voxel_size > 0 ? params.voxel_size : field_B->spacing();
  auto shell = std::make_shared<const Pointshell>(BuildVpsPointshell(*in.A.field(), v, in.A.sampling_seed()));
  return std::make_unique<VpsContactModel>("vps", std::move(shell), std::move(field_B), params);
}

}  // namespace

void RegisterVpsContactModels() {
  RegisterContactModel({
      .name = "vps",
      .description = "Voxmap-PointShell (McNeely et al. 1999/2006): voxel-centre pointshell, tangent-plane forces",
      .needs = {.field_A = true, .field_B = true, .depth_in_field_voxels = true},
      .make = MakeVps,
  });
  RegisterContactModel({
      .name = "vps-repulsion",
      .description = "VPS tangent-plane forces on the scene's own (repulsion) pointshell of A",
      .needs = {.pointshell_A = true, .field_B = true, .depth_in_field_voxels = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return std::make_unique<VpsContactModel>("vps-repulsion", in.A.pointshell(), in.B.field(), VpsParams(in.params));
      },
  });
}

}  // namespace contactlab
