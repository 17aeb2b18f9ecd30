#include "contact/model_registry.h"

#include <algorithm>
#include <map>
#include <type_traits>

#include "contact/deformable_contact_models.h"
#include "contact/pointshell_contact_model.h"
#include "util/error.h"

namespace contactlab {
namespace {

// What each side of the paper's model is made from (contact/rigid_sides.h, deformable_sides.h).
RigidShell::Source SideSource(ContactBody& A, std::type_identity<RigidShell>) { return A.pointshell(); }
DeformableShell::Source SideSource(ContactBody& A, std::type_identity<DeformableShell>) {
  return A.deformable_pointshell();
}
GridField::Source SideSource(ContactBody& B, std::type_identity<GridField>) { return B.field(); }
DeformedField::Source SideSource(ContactBody& B, std::type_identity<DeformedField>) { return B.deformed_field(); }

// The paper's model for the bodies' sides: the shell side from A, the field side from B.
template <class Shell, class Field>
std::unique_ptr<ContactModel> MakePaperModel(PointshellVariant variant, const ContactModelInputs& in) {
  return std::make_unique<PointshellFieldModel<Shell, Field>>(variant, SideSource(in.A, std::type_identity<Shell>{}),
                                                               SideSource(in.B, std::type_identity<Field>{}), in.params);
}
template <class Shell>
std::unique_ptr<ContactModel> MakePaperModelFor(PointshellVariant variant, const ContactModelInputs& in) {
  return in.B.deformable() ? MakePaperModel<Shell, DeformedField>(variant, in) : MakePaperModel<Shell, GridField>(variant, in);
}

ContactModelEntry PaperModel(PointshellVariant variant) {
  const bool linear = variant == PointshellVariant::kLinear;
  ContactModelEntry e;
  e.name = linear ? "pointshell-linear" : "pointshell";
  e.description = linear ? "Barbič & James 2008: every point of one pointshell level against B's field"
                         : "Barbič & James 2008: breadth-first pointshell tree against B's field";
  e.needs.pointshell_A = true;
  e.needs.field_B = true;
  e.needs.depth_in_field_voxels = true;
  e.needs.deformable_A = true;
  e.needs.deformable_B = true;
  e.check = [variant](const PointshellContactParams& params, bool, bool deformable_B, std::string_view where) {
    CheckPointshellCoherence(params, variant, deformable_B, where);
  };
  e.make = [variant](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    return in.A.deformable() ? MakePaperModelFor<DeformableShell>(variant, in) : MakePaperModelFor<RigidShell>(variant, in);
  };
  return e;
}

std::map<std::string, ContactModelEntry, std::less<>>& Registry() {
  static std::map<std::string, ContactModelEntry, std::less<>> registry = [] {
    std::map<std::string, ContactModelEntry, std::less<>> r;
    for (auto v : {PointshellVariant::kTree, PointshellVariant::kLinear}) {
      ContactModelEntry e = PaperModel(v);
      r[e.name] = std::move(e);
    }
    return r;
  }();
  return registry;
}

}  // namespace

void RegisterContactModel(ContactModelEntry entry) {
  if (entry.name.empty() || !entry.make) Fail("contact model registry", "an entry needs a name and a factory");
  std::string name = entry.name;
  Registry()[name] = std::move(entry);
}

const ContactModelEntry* FindContactModel(std::string_view name) {
  const auto& registry = Registry();
  const auto it = registry.find(name);
  return it == registry.end() ? nullptr : &it->second;
}

void CheckContactModel(std::string_view name, const PointshellContactParams& params, std::string_view body_A,
                       bool deformable_A, std::string_view body_B, bool deformable_B, std::string_view where) {
  const ContactModelEntry* entry = FindContactModel(name);
  if (entry == nullptr) {
    std::string known;
    for (const std::string& n : ContactModelNames()) known += (known.empty() ? "" : ", ") + n;
    for (const std::string& n : ReferenceModelNames()) known += (known.empty() ? "" : ", ") + n + " (reference)";
    Fail(where, "unknown contact model '" + std::string(name) + "' (known: " + known + ")");
  }
  if (deformable_A && !entry->needs.deformable_A) {
    Fail(where, "contact model '" + std::string(name) + "' treats body A as rigid, but '" + std::string(body_A) +
                    "' is deformable (models that deform it: pointshell, pointshell-linear)");
  }
  if (deformable_B && !entry->needs.deformable_B) {
    Fail(where, "contact model '" + std::string(name) + "' treats body B as rigid, but '" + std::string(body_B) +
                    "' is deformable (models that deform it: pointshell, pointshell-linear)");
  }
  if (entry->check) entry->check(params, deformable_A, deformable_B, where);
}

std::unique_ptr<ContactModel> MakeContactModel(std::string_view name, const ContactModelInputs& inputs,
                                               std::string_view where) {
  CheckContactModel(name, inputs.params, inputs.A.body_name(), inputs.A.deformable(), inputs.B.body_name(),
                    inputs.B.deformable(), where);
  return FindContactModel(name)->make(inputs);
}

std::vector<std::string> ContactModelNames() {
  std::vector<std::string> names;
  for (const auto& [n, e] : Registry()) {
    if (!e.reference_only) names.push_back(n);
  }
  return names;
}

std::vector<std::string> ReferenceModelNames() {
  std::vector<std::string> names;
  for (const auto& [n, e] : Registry()) {
    if (e.reference_only) names.push_back(n);
  }
  return names;
}

}  // namespace contactlab
