// Experiment configs (experiments/*.yaml): a scene, the models to compare, a trajectory, the
// metrics, and sweep axes. Every sweep point is a job; jobs can be listed and run one at a
// time (a cluster array) and their results merged.
//
//   name: fig5b-convergence
//   description: ...
//   scene: scenes/sphere-on-plate.yaml     # a scene file, or an inline scene mapping
//   models: [pointshell-linear]            # default: the scene's models
//   moving_body: plate                     # body that follows the trajectory (default: field body)
//   trajectory: {type: approach-press, direction: [0, 0, 1], depth: 0.002, duration: 1}
//   reference: reference                   # model evaluated as ground truth ('' = none), or
//   reference: {model: pointshell-linear, points: 65536, levels: 1}  # a denser version of the scene
//   reference_every: 10                    # evaluate the reference every N cycles
//   metrics: {cutoff_hz: 100, timing: false}
//   sweep: {points: [1024, 4096, 16384]}   # axes: points levels method resolution
//                                          # pointshell_resolution k_C node_budget coherence
//                                          # max_point_speed level model roles gradient
//                                          # scene (a scene file per job), offset (the
//                                          # pointshell's level-set offset, m, or default)
//   profiles: {paper: {sweep.points: [...]}} # named sets of overrides: --profile paper
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "experiment/scene.h"
#include "experiment/trajectory.h"
#include "util/config_node.h"

namespace contactlab {

struct SweepAxis {
  std::string name;
  std::vector<std::string> values;  // scalar texts, applied by ApplySweepValue
};

struct ExperimentConfig {
  std::string name;
  std::string description;
  std::string file;
  std::string resolved_yaml;   // the config after --set overrides, as YAML text
  Scene scene;
  std::vector<std::string> models;
  std::string moving_body;     // body name
  bool moving_body_is_default = true;  // not given: each job's field body
  ConfigNode trajectory_node;  // parsed per job (recorded files are read once per job)
  std::string reference_model;
  int reference_points = 0;      // > 0: the reference scene's pointshell points
  int reference_levels = 0;      // > 0: ... and levels
  int reference_resolution = 0;  // > 0: the reference scene's field resolution
  int reference_every = 1;
  double cutoff_hz = 100;
  bool timing = false;         // per-cycle times matter: run jobs one at a time
  std::vector<SweepAxis> sweep;
};

struct Job {
  int index = 0;
  std::vector<std::pair<std::string, std::string>> axis_values;  // (axis, value) per sweep axis
  Scene scene;
  std::vector<std::string> models;
  std::string moving_body;
  std::string Label() const;  // "points=1024 model=vps"
};

// Reads CONFIG_FILE, applies OVERRIDES ("key.path=value", value parsed as YAML) and checks
// every key. Throws Error naming the file (or the override) and the key.
// PROFILE (may be empty) names an entry of the config's "profiles" whose overrides apply
// before OVERRIDES.
ExperimentConfig LoadExperimentConfig(const std::filesystem::path& config_file,
                                      const std::vector<std::string>& overrides = {},
                                      const std::string& profile = "");
ExperimentConfig ParseExperimentConfig(const ConfigNode& root, std::string resolved_yaml);

// The cartesian product of the sweep axes, in order (the last axis varies fastest).
std::vector<Job> ExpandJobs(const ExperimentConfig& config);

// Applies one sweep value to JOB (scene, models, roles); throws Error naming the axis.
void ApplySweepValue(const std::string& axis, const std::string& value, Job* job, const std::string& where);

}  // namespace contactlab
