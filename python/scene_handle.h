// What the Python objects of one scene share: the parsed scene and its bodies' data (built on
// first use, through the on-disk cache), kept alive by every Body and Model made from it.
#pragma once

#include <memory>

#include "scene/scene.h"
#include "scene/scene_assets.h"

namespace contactlab::python {

struct SceneHandle {
  SceneHandle(Scene s, const AssetOptions& options) : scene(Checked(std::move(s))), assets(scene, options) {}
  Scene scene;
  SceneAssets assets;

 private:
  // The module's Scene holds two bodies; a scene of many bodies is refused by name.
  static Scene Checked(Scene s) {
    s.RequireTwoBodies("the Python module's Scene");
    return s;
  }
};

}  // namespace contactlab::python
