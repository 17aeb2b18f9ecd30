// Registers "fcl" (FclContactModel on A's and B's meshes, the scene's k_C and L, and its own
// keys fcl_bv, fcl_max_contacts, fcl_shape: fcl_params.h) with the contact-model
// registry.
#include <memory>

#include "baselines/fcl/fcl_contact_model.h"
#include "baselines/fcl/fcl_params.h"
#include "contact/model_registry.h"

namespace contactlab {

void RegisterFclContactModels() {
  RegisterContactModel({
      .name = "fcl",
      .description = "FCL 0.7 mesh-mesh contacts (OBBRSS) as penalty contacts",
      .needs = {.mesh_A = true, .mesh_B = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return std::make_unique<FclContactModel>(
            in.A.mesh(), in.B.mesh(), FclContactParams{
                .penalty = in.params.penalty, .own = in.Params(FclOwnParamTable()), .friction = in.params.friction});
      },
      .mesh_pair_contacts = true,
      .friction = FrictionSupport::kRigidBodies,
      .pair_params = ParamBlock(FclOwnParamTable()),
  });
}

}  // namespace contactlab
