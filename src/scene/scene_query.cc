#include "scene/scene_query.h"

#include "geometry/triangle_mesh.h"

namespace contactlab {

ContactQuery SceneContactQuery(const Scene& scene, const Pose& X_WA, const Pose& X_WB, std::int64_t cycle) {
  ContactQuery q;
  q.X_WA = X_WA;
  q.X_WB = X_WB;
  q.cycle = cycle;
  q.node_budget = scene.node_budget;
  return q;
}

HapticCycleConfig SceneCycleConfig(const Scene& scene, SceneAssets& assets, SceneDynamics* dynamics) {
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  config.node_budget = scene.node_budget;
  config.max_point_speed = scene.model.max_point_speed;
  config.cycle_seconds = scene.model.cycle_seconds;
  config.body_radius_H = assets.B.mesh()->MaxVertexRadius();
  if (dynamics != nullptr) {
    config.dynamics_A = dynamics->A.get();
    config.dynamics_B = dynamics->B.get();
  }
  return config;
}

}  // namespace contactlab
