// Registers the paper's model (Barbič & James 2008) with the contact-model registry, exactly as
// every baseline registers: "pointshell" (breadth-first traversal of the pointshell tree, sec. 3)
// and "pointshell-linear" (every point of one level). Each body's side is chosen from what the
// body is: a rigid or deformable shell (sec. 4.1) for A, a grid or deformed field (sec. 4.2) for
// B, combined by templates (rigid_sides.h, deformable_sides.h).
#include <memory>
#include <type_traits>

#include "contact/model_registry.h"
#include "pointshell_contact/deformable_contact_models.h"
#include "pointshell_contact/pointshell_contact_model.h"

namespace contactlab {
namespace {

// What each side of the paper's model is made from.
RigidShell::Source SideSource(ContactBody& A, std::type_identity<RigidShell>) { return A.pointshell(); }
DeformableShell::Source SideSource(ContactBody& A, std::type_identity<DeformableShell>) {
  return A.deformable_pointshell();
}
GridField::Source SideSource(ContactBody& B, std::type_identity<GridField>) { return B.field(); }
DeformedField::Source SideSource(ContactBody& B, std::type_identity<DeformedField>) { return B.deformed_field(); }

// The paper's model for the bodies' sides: the shell side from A, the field side from B.
template <class Shell, class Field>
std::unique_ptr<ContactModel> MakePaperModel(PointshellVariant variant, const ContactModelInputs& in) {
  return std::make_unique<PointshellFieldModel<Shell, Field>>(
      variant, SideSource(in.A, std::type_identity<Shell>{}), SideSource(in.B, std::type_identity<Field>{}),
      PointshellParamsOf(in.params, in.Params(PointshellOwnParamTable())));
}
template <class Shell>
std::unique_ptr<ContactModel> MakePaperModelFor(PointshellVariant variant, const ContactModelInputs& in) {
  return in.B.deformable() ? MakePaperModel<Shell, DeformedField>(variant, in) : MakePaperModel<Shell, GridField>(variant, in);
}

// The harness's depth probe (ContactModelEntry::make_depth_probe): every point of the deepest
// level, on the rigid sides (the rest shapes), with the scene's other parameters.
std::unique_ptr<ContactModel> MakeDepthProbe(const ContactModelInputs& in) {
  PointshellContactParams params = PointshellParamsOf(in.params, in.Params(PointshellOwnParamTable()));
  params.level = -1;
  params.friction = {};  // depths only
  return std::make_unique<PointshellContactModel>(PointshellContactModel::Variant::kLinear, in.A.pointshell(),
                                                  in.B.field(), params);
}

ContactModelEntry PaperModel(PointshellVariant variant) {
  const bool linear = variant == PointshellVariant::kLinear;
  return {
      .name = linear ? "pointshell-linear" : "pointshell",
      .description = linear ? "Barbič & James 2008: every point of one pointshell level against B's field"
                            : "Barbič & James 2008: breadth-first pointshell tree against B's field",
      .needs = {.pointshell_A = true,
                .field_B = true,
                .depth_in_field_voxels = true,
                .deformable_A = true,
                .deformable_B = true},
      .make = [variant](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return in.A.deformable() ? MakePaperModelFor<DeformableShell>(variant, in)
                                 : MakePaperModelFor<RigidShell>(variant, in);
      },
      .friction = FrictionSupport::kRigidBodies,
      .pair_params = ParamBlock(PointshellOwnParamTable()),
      .make_depth_probe = linear ? ContactModelFactory(MakeDepthProbe) : nullptr,
      .stiffness_reference = !linear,
      .at_full_detail = [](ParamValues& own) { own.Mutable(PointshellOwnParamTable()).level = -1; },
      .check = [variant](const ContactParams& params, const ParamValues& own, bool, bool deformable_B,
                         std::string_view where) {
        CheckPointshellCoherence(PointshellParamsOf(params, own.Get(PointshellOwnParamTable())), variant,
                                 deformable_B, where);
      },
  };
}

}  // namespace

void RegisterPointshellContactModels() {
  for (const PointshellVariant v : {PointshellVariant::kTree, PointshellVariant::kLinear}) RegisterContactModel(PaperModel(v));
}

}  // namespace contactlab
