// Registers "pressure-field" (pressure_field_model.h) with the contact-model registry. Each
// body's modulus (or rigidity) comes from its scene block `pressure_field:`; the fields are the
// bodies' own distance fields.
#include <memory>

#include "baselines/pressure_field/pressure_field_model.h"
#include "contact/model_registry.h"

namespace contactlab {

void RegisterPressureFieldContactModels() {
  ContactModelEntry e;
  e.name = "pressure-field";
  e.description = "hydroelastic contact: pressure fields inside both bodies, wrench over the equal-pressure surface (Elandt et al. 2019)";
  e.needs.field_A = true;
  e.needs.field_B = true;
  e.contact_surface = true;
  e.make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    // k_C does not enter this model, but a scene's penalty parameters are checked by every model.
    CheckPenaltyParams(in.params.penalty, "pressure-field");
    auto side = [](ContactBody& body) {
      const PressureFieldSpec& s = body.contact_params().pressure_field;
      return PressureFieldSide{body.field(), s.modulus, s.rigid};
    };
    PressureFieldOptions o;
    o.lipschitz = in.params.lipschitz;
    o.lattice = in.params.pressure_lattice;
    return std::make_unique<PressureFieldModel>(side(in.A), side(in.B), o);
  };
  RegisterContactModel(std::move(e));
}

}  // namespace contactlab
