// Registers "bullet" (BulletContactModel on A's and B's meshes, the scene's k_C and L) with
// the contact-model registry.
#include <memory>

#include "baselines/bullet/bullet_contact_model.h"
#include "contact/model_registry.h"

namespace contactlab {

void RegisterBulletContactModels() {
  ContactModelEntry e;
  e.name = "bullet";
  e.description = "Bullet GImpact contact manifolds as penalty contacts";
  e.needs.mesh_A = true;
  e.needs.mesh_B = true;
  e.make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    BulletContactParams p;
    p.penalty = in.params.penalty;
    return std::make_unique<BulletContactModel>(in.A.mesh(), in.B.mesh(), p);
  };
  RegisterContactModel(std::move(e));
}

}  // namespace contactlab
