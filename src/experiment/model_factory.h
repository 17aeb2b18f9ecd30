// Contact models made by name from a scene (DESIGN.md), so one experiment config can list
// several and compare them. The paper's models are built in; baselines register theirs.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_model.h"
#include "contact/pointshell_contact_model.h"
#include "experiment/scene.h"
#include "experiment/scene_assets.h"

namespace contactlab {

using ContactModelFactory = std::function<std::unique_ptr<ContactModel>(const Scene&, SceneAssets&)>;

// Adds (or replaces) the factory for NAME.
void RegisterContactModel(const std::string& name, ContactModelFactory factory);

// Makes model NAME for SCENE, building the assets it needs. Throws Error listing the known
// names when NAME is unknown.
std::unique_ptr<ContactModel> MakeContactModel(std::string_view name, const Scene& scene, SceneAssets& assets);

// Every registered name, sorted.
std::vector<std::string> ContactModelNames();

// The paper's model parameters from a scene's model section.
PointshellContactParams PointshellParamsFromScene(const Scene& scene);

}  // namespace contactlab
