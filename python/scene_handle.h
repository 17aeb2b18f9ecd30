// What the Python objects of one scene share: the parsed scene and its bodies' data (built on
// first use, through the on-disk cache), kept alive by every Body and Model made from it.
#pragma once

#include <memory>

#include "scene/scene.h"
#include "scene/scene_assets.h"

namespace contactlab::python {

struct SceneHandle {
  SceneHandle(Scene s, const AssetOptions& options) : scene(std::move(s)), assets(scene, options) {}
  Scene scene;
  SceneAssets assets;
};

}  // namespace contactlab::python
