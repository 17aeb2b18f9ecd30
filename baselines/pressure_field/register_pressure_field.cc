// Registers "pressure-field" (pressure_field_model.h) with the contact-model registry, with its
// own parameters: per body, the block `pressure_field:` (its modulus, or rigid), and in the
// scene's model section the lattice its contact surface is extracted on. The fields are the
// bodies' own distance fields.
#include <memory>

#include "baselines/pressure_field/pressure_field_model.h"
#include "baselines/pressure_field/pressure_field_params.h"
#include "contact/model_registry.h"

namespace contactlab {
namespace {

std::unique_ptr<ContactModel> MakePressureField(const ContactModelInputs& in) {
  // k_C does not enter this model, but a scene's penalty parameters are checked by every model.
  CheckPenaltyParams(in.params.penalty, "pressure-field");
  auto side = [](ContactBody& body) {
    const PressureFieldSpec& s = body.model_blocks().Get(PressureFieldParams());
    return PressureFieldSide{body.field(), s.modulus, s.rigid};
  };
  PressureFieldOptions o;
  o.lipschitz = in.params.lipschitz;
  o.lattice = in.Params(PressureLatticeParams()).lattice;
  return std::make_unique<PressureFieldModel>(side(in.A), side(in.B), o);
}

}  // namespace

void RegisterPressureFieldContactModels() {
  RegisterContactModel({
      .name = "pressure-field",
      .description = "hydroelastic contact: pressure fields inside both bodies, wrench over the equal-pressure "
                     "surface (Elandt et al. 2019)",
      .needs = {.field_A = true, .field_B = true},
      .make = MakePressureField,
      .contact_surface = true,
      .pair_params = ParamBlock(PressureLatticeParams()),
      .body_blocks = {ParamBlock(PressureFieldParams(), "pressure_field",
                                 "its pressure field in the pressure-field model")},
  });
}

}  // namespace contactlab
