// Shared by the contact benchmarks: a scene loaded with its assets and body A placed at a
// shallow and a deep penetration along the line from A's start pose to B's origin, so every
// program times the same configurations.
#pragma once

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "contact/contact_model.h"
#include "pointshell_contact/pointshell_contact_params.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "geometry/pose.h"

namespace contactlab {

// The parameters of the paper's model in SCENE: the model section's shared keys and the
// paper's own (level, cold_fraction, gradient), for the benchmarks that make it directly.
inline PointshellContactParams PaperModelParams(const Scene& scene) {
  return PointshellParamsOf(scene.model, scene.model_params.Get(PointshellOwnParamTable()));
}

}  // namespace contactlab

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
// paper's linear model at kDepths (scene/contact_placement.h TouchAlong); with ADD_OFFSET the target depth grows by the
// pointshell's offset, so the meshes themselves (not the offset surface) overlap by about
// kDepths, as the mesh-based models need. Cached per argument set for the program's lifetime.
// CONTACTLAB_BENCH_FIELD=STORAGE:RESOLUTION (e.g. sparse:1024, dense:256) replaces the field
// body's field spec in every scene, to time the models on another field; a malformed value
// stops the program with a message.
PlacedScene& PreparePlacedScene(const std::string& scene_file, int points, int levels, bool add_offset);

// Sums over the timed cycles of TimeCirclingCycles (divide by cycles for means).
struct CycleTimes {
  std::int64_t cycles = 0;
  double nodes = 0, contacts = 0, level = 0;  // sums of the per-cycle statistics
  double max_us = 0;                          // slowest cycle
};

// The timed loop of the contact benchmarks: one MODEL.Evaluate per iteration with A at the
// DEPTH placement of P, sliding on a 1 mm circle (6 mm/s) across B so temporal coherence sees
// a moving configuration. Sets the counters contacts, max_us, p99_us and p999_us (cycle time
// percentiles; the slowest cycle includes the operating system's jitter) and the items
// processed (nodes visited).
CycleTimes TimeCirclingCycles(benchmark::State& state, ContactModel& model, const PlacedScene& p, int depth,
                              std::int64_t node_budget = 0);

}  // namespace contactlab::bench
