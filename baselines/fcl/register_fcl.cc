// Registers "fcl" (FclContactModel on A's and B's meshes, the scene's k_C and L) with the
// contact-model registry.
#include <memory>

#include "baselines/fcl/fcl_contact_model.h"
#include "contact/model_registry.h"

namespace contactlab {

void RegisterFclContactModels() {
  ContactModelEntry e;
  e.name = "fcl";
  e.description = "FCL 0.7 mesh-mesh contacts (OBBRSS) as penalty contacts";
  e.needs.mesh_A = true;
  e.needs.mesh_B = true;
  e.make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    FclContactParams p;
    p.penalty = in.params.penalty;
    return std::make_unique<FclContactModel>(in.A.mesh(), in.B.mesh(), p);
  };
  RegisterContactModel(std::move(e));
}

}  // namespace contactlab
