#include "experiment/model_factory.h"

#include <algorithm>
#include <map>

#include "contact/pointshell_contact_model.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::map<std::string, ContactModelFactory, std::less<>>& Registry() {
  static std::map<std::string, ContactModelFactory, std::less<>> registry = [] {
    std::map<std::string, ContactModelFactory, std::less<>> r;
    r["pointshell"] = [](const Scene& scene, SceneAssets& assets) -> std::unique_ptr<ContactModel> {
      return std::make_unique<PointshellContactModel>(PointshellContactModel::Variant::kTree, assets.A.pointshell(),
                                                      assets.B.field(), PointshellParamsFromScene(scene));
    };
    r["pointshell-linear"] = [](const Scene& scene, SceneAssets& assets) -> std::unique_ptr<ContactModel> {
      return std::make_unique<PointshellContactModel>(PointshellContactModel::Variant::kLinear, assets.A.pointshell(),
                                                      assets.B.field(), PointshellParamsFromScene(scene));
    };
    return r;
  }();
  return registry;
}

}  // namespace

PointshellContactParams PointshellParamsFromScene(const Scene& scene) {
  const ModelSpec& m = scene.model;
  PointshellContactParams p;
  p.k_C = m.k_C;
  p.L = m.L;
  p.level = m.level;
  p.coherence = m.coherence;
  p.max_point_speed = m.max_point_speed;
  p.cycle_seconds = m.cycle_seconds;
  p.lipschitz = m.lipschitz;
  p.cold_fraction = m.cold_fraction;
  p.gradient = m.gradient;
  return p;
}

void RegisterContactModel(const std::string& name, ContactModelFactory factory) {
  Registry()[name] = std::move(factory);
}

std::unique_ptr<ContactModel> MakeContactModel(std::string_view name, const Scene& scene, SceneAssets& assets) {
  auto& registry = Registry();
  auto it = registry.find(name);
  if (it == registry.end()) {
    std::string known;
    for (const auto& [n, f] : registry) known += (known.empty() ? "" : ", ") + n;
    Fail(scene.file.empty() ? std::string("scene") : scene.file,
         "unknown contact model '" + std::string(name) + "' (known: " + known + ")");
  }
  return it->second(scene, assets);
}

std::vector<std::string> ContactModelNames() {
  std::vector<std::string> names;
  for (const auto& [n, f] : Registry()) names.push_back(n);
  return names;
}

}  // namespace contactlab
