#include "placed_scene.h"

#include <map>

#include "contact/pointshell_contact_model.h"
#include "experiment/contact_placement.h"
#include "experiment/model_factory.h"
#include "util/data_path.h"

namespace contactlab::bench {

PlacedScene& PreparePlacedScene(const std::string& scene_file, int points, int levels, bool add_offset) {
  static std::map<std::string, PlacedScene> cache;
  const std::string key =
      scene_file + "/" + std::to_string(points) + "/" + std::to_string(levels) + (add_offset ? "/offset" : "");
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  PlacedScene& p = cache[key];
  p.scene = LoadScene(RequireDataFile(scene_file));
  if (points > 0) p.scene.pointshell_body.pointshell.points = points;
  if (levels > 0) p.scene.pointshell_body.pointshell.levels = levels;
  AssetOptions options;
  options.verbose = false;
  p.assets = std::make_unique<SceneAssets>(p.scene, options);
  p.X_WB = p.scene.field_body.pose;
  // Approach from the scene's start pose of A toward B's origin, starting 5 cm back.
  const Pose start = p.scene.pointshell_body.pose;
  if ((p.X_WB.translation - start.translation).norm() > 0) {
    p.direction = (p.X_WB.translation - start.translation).normalized();
  }
  PointshellContactModel probe(PointshellContactModel::Variant::kLinear, p.assets->A.pointshell(), p.assets->B.field(),
                               PointshellParamsFromScene(p.scene));
  Pose far = start;
  far.translation -= 0.05 * p.direction;
  const double extra = add_offset ? p.assets->A.pointshell()->offset : 0.0;
  for (int d = 0; d < 2; ++d) {
    const Placement placed = PlaceAtDepth(probe, far, p.X_WB, p.direction, kDepths[d] + extra, 0.3);
    p.placed[d] = placed.found;
    p.X_WA[d] = placed.X_WA;
  }
  return p;
}

}  // namespace contactlab::bench
