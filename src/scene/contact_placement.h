// Putting two bodies into contact at a chosen depth: body A is moved along a direction toward
// B until the deepest penetration a contact model reports reaches the target. Used by
// benchmarks and experiments to make "shallow" and "deep" contact configurations.
#pragma once

#include <Eigen/Core>

#include <string>

#include "contact/contact_model.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "geometry/pose.h"

namespace contactlab {

struct Placement {
  Pose X_WA;            // A's pose with the requested penetration
  double travel = 0;    // distance moved from the start, metres
  double depth = 0;     // penetration reached (max_penetration stat), metres
  bool found = false;   // false when A passed through B's reach without reaching DEPTH
};

// PlaceAtDepth's marches: a coarse one of kPlacementCoarseSteps steps over the travel, then a
// fine one of at most kPlacementFineSteps steps within one coarse step; with its bisection of at
// most kPlacementMaxBisections halvings, any DEPTH > 0 is placed with at most 8,260 queries.
inline constexpr int kPlacementCoarseSteps = 4096;
inline constexpr int kPlacementFineSteps = 4096;
inline constexpr int kPlacementMaxBisections = 64;

// Starts A at X_WA_START (separated from B) and moves it by s * DIRECTION (world, normalised
// here) for s in [0, MAX_TRAVEL] to the first s whose penetration (stats.max_penetration of
// MODEL) reaches DEPTH: a coarse march in steps of MAX_TRAVEL / kPlacementCoarseSteps finds the
// coarse step where it does, a fine march in steps of DEPTH / 4 (never finer than a
// kPlacementFineSteps-th of a coarse step) the fine step within it, and a bisection the
// position to 1 % of DEPTH or to the resolution of s. The fine steps before the coarse step
// short of DEPTH are taken as short of it too: a feature thinner than a coarse step along
// DIRECTION may be stepped over. The model must report max_penetration (the pointshell models
// do).
Placement PlaceAtDepth(ContactModel& model, const Pose& X_WA_start, const Pose& X_WB, Eigen::Vector3d direction,
                       double depth, double max_travel);

// Moves one body of SCENE (B when MOVE_B, else A; the other stays at its pose) along
// DIRECTION (world) from far enough back that the bodies are apart, until the paper's model
// (linear, deepest level, the scene's parameters) reports DEPTH of penetration. Returns the
// moved body's new pose. Throws Error naming WHERE when the bodies never touch.
Pose TouchAlong(const Scene& scene, SceneAssets& assets, bool move_B, const Pose& X_WA, const Pose& X_WB,
                const Eigen::Vector3d& direction, double depth, const std::string& where);

}  // namespace contactlab
