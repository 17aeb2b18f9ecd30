// Registers "bullet" (BulletContactModel on A's and B's meshes, the scene's k_C and L, and its
// own keys bullet_margin, bullet_subtract_margins, bullet_shape: bullet_params.h) with the
// contact-model registry.
#include <memory>

#include "baselines/bullet/bullet_contact_model.h"
#include "baselines/bullet/bullet_params.h"
#include "contact/model_registry.h"

namespace contactlab {

void RegisterBulletContactModels() {
  RegisterContactModel({
      .name = "bullet",
      .description = "Bullet GImpact contact manifolds as penalty contacts",
      .needs = {.mesh_A = true, .mesh_B = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return std::make_unique<BulletContactModel>(
            in.A.mesh(), in.B.mesh(),
            BulletContactParams{
                .penalty = in.params.penalty, .own = in.Params(BulletOwnParamTable()), .friction = in.params.friction});
      },
      .allocates = true,  // GImpact's triangle-pair list, per query
      .mesh_pair_contacts = true,
      .friction = FrictionSupport::kRigidBodies,
      .pair_params = ParamBlock(BulletOwnParamTable()),
  });
}

}  // namespace contactlab
