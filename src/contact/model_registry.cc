#include "contact/model_registry.h"

#include <algorithm>
#include <atomic>
#include <map>

#include "contact/unbuilt_models.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::map<std::string, ContactModelEntry, std::less<>>& Registry() {
  static std::map<std::string, ContactModelEntry, std::less<>> registry;
  return registry;
}

std::atomic<std::uint64_t> registry_version{0};

// The registered names whose entry's NEEDS member says it renders that body's deformation, as
// a list for messages.
std::string ModelsThatDeform(bool ContactModelNeeds::*renders) {
  std::string list;
  for (const auto& [n, e] : Registry()) {
    if (e.needs.*renders) list += (list.empty() ? "" : ", ") + n;
  }
  return list.empty() ? "none" : list;
}

}  // namespace

void RegisterContactModel(ContactModelEntry entry) {
  if (entry.name.empty() || !entry.make) Fail("contact model registry", "an entry needs a name and a factory");
  std::string name = entry.name;
  Registry()[name] = std::move(entry);
  ++registry_version;
}

std::uint64_t ContactModelRegistryVersion() { return registry_version.load(); }

std::vector<const ContactModelEntry*> ContactModelEntries() {
  std::vector<const ContactModelEntry*> entries;
  for (const auto& [n, e] : Registry()) entries.push_back(&e);
  return entries;
}

const ContactModelEntry* FindContactModel(std::string_view name) {
  const auto& registry = Registry();
  const auto it = registry.find(name);
  return it == registry.end() ? nullptr : &it->second;
}

const ContactModelEntry& SoleContactModelWith(const std::function<bool(const ContactModelEntry&)>& has,
                                              std::string_view trait, std::string_view where) {
  const ContactModelEntry* sole = nullptr;
  for (const auto& [n, e] : Registry()) {
    if (!has(e)) continue;
    if (sole != nullptr) {
      Fail(where, "several registered contact models declare " + std::string(trait) + ": " + sole->name + ", " + e.name);
    }
    sole = &e;
  }
  if (sole == nullptr) Fail(where, "no registered contact model declares " + std::string(trait));
  return *sole;
}

void CheckContactModel(std::string_view name, const ContactParams& params, const ParamValues& model_params,
                       std::string_view body_A, bool deformable_A, std::string_view body_B, bool deformable_B,
                       std::string_view where) {
  const ContactModelEntry* entry = FindContactModel(name);
  if (entry == nullptr) {
    if (const std::optional<std::string> reason = UnbuiltContactModelReason(name)) {
      Fail(where, "contact model '" + std::string(name) + "' is not built into this program: " + *reason);
    }
    std::string known;
    for (const std::string& n : ContactModelNames()) known += (known.empty() ? "" : ", ") + n;
    for (const std::string& n : ReferenceModelNames()) known += (known.empty() ? "" : ", ") + n + " (reference)";
    Fail(where, "unknown contact model '" + std::string(name) + "' (known: " + known + ")");
  }
  if (deformable_A && !entry->needs.deformable_A) {
    Fail(where, "contact model '" + std::string(name) + "' treats body A as rigid, but '" + std::string(body_A) +
                    "' is deformable (models that deform it: " + ModelsThatDeform(&ContactModelNeeds::deformable_A) + ")");
  }
  if (deformable_B && !entry->needs.deformable_B) {
    Fail(where, "contact model '" + std::string(name) + "' treats body B as rigid, but '" + std::string(body_B) +
                    "' is deformable (models that deform it: " + ModelsThatDeform(&ContactModelNeeds::deformable_B) + ")");
  }
  if (params.friction.on()) {
    if (entry->friction == FrictionSupport::kNone) {
      std::string carry;
      for (const std::string& n : ContactModelNames()) {
        if (FindContactModel(n)->friction != FrictionSupport::kNone) carry += (carry.empty() ? "" : ", ") + n;
      }
      Fail(where, "contact model '" + std::string(name) + "' carries no friction, but friction.static is " +
                      param_detail::Number(params.friction.mu_static) + " (models that carry it: " + carry +
                      "; `contactlab models` lists them)");
    }
    if (entry->friction == FrictionSupport::kRigidBodies && (deformable_A || deformable_B)) {
      Fail(where, "contact model '" + std::string(name) + "' carries friction between rigid bodies only, but '" +
                      std::string(deformable_A ? body_A : body_B) + "' is deformable (set friction.static: 0 for this pair)");
    }
  }
  if (entry->check) entry->check(params, model_params, deformable_A, deformable_B, where);
}

std::unique_ptr<ContactModel> MakeContactModel(std::string_view name, const ContactModelInputs& inputs,
                                               std::string_view where) {
  CheckContactModel(name, inputs.params, inputs.model_params, inputs.A.body_name(), inputs.A.deformable(), inputs.B.body_name(),
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
