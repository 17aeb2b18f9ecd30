// Contact models the project has but this program was built without (the CGAL references in a
// build configured with -DCONTACTLAB_WITH_CGAL=OFF): their names and why, so that a config
// naming one is told what is missing instead of "unknown model", and a misspelled name can be
// told from a model that is only absent here.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace contactlab {

// Records that model NAME exists but is not built into this program, and REASON (what to
// build it with). Called by a model folder's registration in place of RegisterContactModel.
void RegisterUnbuiltContactModel(std::string name, std::string reason);

// The reason given for NAME by RegisterUnbuiltContactModel, or nothing when NAME was not so
// recorded (registered as a model, or unknown).
std::optional<std::string> UnbuiltContactModelReason(std::string_view name);

}  // namespace contactlab
