// Shared by the contact benchmarks: a scene loaded with its assets and body A placed at a
// shallow and a deep penetration along the line from A's start pose to B's origin, so every
// program times the same configurations.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "experiment/scene.h"
#include "experiment/scene_assets.h"
#include "geometry/pose.h"

namespace contactlab::bench {

inline constexpr double kDepths[2] = {0.0005, 0.002};  // shallow 0.5 mm, deep 2 mm
inline const char* const kDepthNames[2] = {"shallow", "deep"};

struct PlacedScene {
  Scene scene;
  std::unique_ptr<SceneAssets> assets;
  Pose X_WB;                 // B at the scene's pose
  Pose X_WA[2];              // A at the shallow and the deep placement
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // approach direction (world)
  bool placed[2] = {false, false};
  bool ok() const { return placed[0] && placed[1]; }
};

// Loads SCENE_FILE (A's pointshell gets POINTS and LEVELS when > 0) and places A with the
// paper's linear model at kDepths; with ADD_OFFSET the target depth grows by the
// pointshell's offset, so the meshes themselves (not the offset surface) overlap by about
// kDepths, as the mesh-based models need. Cached per argument set for the program's lifetime.
PlacedScene& PreparePlacedScene(const std::string& scene_file, int points, int levels, bool add_offset);

}  // namespace contactlab::bench
