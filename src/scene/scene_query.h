// The one contact query and the one haptic-cycle configuration built from a scene
// (docs/architecture.md, "Layers"): every caller that queries a scene's model (the contact
// study, `contact`, the viewer, Python, the benchmarks) or closes a haptic loop on it (the
// closed-loop study, `session`) builds them here, so a scene key such as model.node_budget
// reaches each of them alike.
#pragma once

#include <cstdint>

#include "contact/contact_model.h"
#include "geometry/pose.h"
#include "haptics/haptic_cycle.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"

namespace contactlab {

// The query of SCENE's bodies at world poses X_WA (the pointshell body) and X_WB (the field
// body) as haptic cycle CYCLE, under the scene's node budget (model.node_budget; 0: unlimited).
// Both bodies rigid: a caller with a deformable body sets deformation_A / deformation_B.
ContactQuery SceneContactQuery(const Scene& scene, const Pose& X_WA, const Pose& X_WB, std::int64_t cycle = 0);

// The haptic cycle of SCENE (paper sec. 5): A static at its scene pose, the field body the
// haptic body H, the scene's node budget, the coherence guard from model.max_point_speed and
// model.cycle_seconds with H's bounding radius (ASSETS' field-body mesh), and the bodies'
// dynamics from DYNAMICS (null, or an entry null: that body rigid; must outlive the cycle).
// The coupling, safety and view marks keep their defaults for the caller to set.
HapticCycleConfig SceneCycleConfig(const Scene& scene, SceneAssets& assets, SceneDynamics* dynamics);

}  // namespace contactlab
