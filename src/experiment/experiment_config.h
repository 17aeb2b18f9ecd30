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
//   reference: volume                      # model evaluated as ground truth ('' = none): volume
//                                          # (the exact overlap volume's law, model-independent),
//                                          # reference (the eq. (2) limit), any model, or
//   reference: {model: pointshell-linear, points: 65536, levels: 1}  # a denser version of the scene
//   reference_every: 10                    # evaluate the reference every N cycles
//   metrics: {cutoff_hz: 100, timing: false}
//   sweep: {points: [1024, 4096, 16384]}   # an axis is a key path or a short alias (below)
//   profiles: {paper: {sweep.points: [...]}} # named sets of overrides: --profile paper
//                                          # (as --set: "sweep.AXIS" replaces the axis AXIS
//                                          # whole, also an axis named by a key path)
//   study: contact                         # contact (default): models along a trajectory;
//                                          # deformed-field: the field body's deformed distance
//                                          # field against the exact one (deformed_field_study.h),
//                                          # with 'deformation' and 'measure' sections instead of
//                                          # models, trajectory and reference
//
// Sweeps are overrides: each job's value is written at the axis's key path into the config
// document (paths under "scene." into the scene's document, also when the scene is a file),
// then the scene is parsed again, so every check lives in the scene parser and any key is
// sweepable. A path is dot-separated keys; a list element is picked by index or by a field,
// e.g. scene.bodies[role=field].field.resolution, scene.bodies[name=dragon].scale,
// trajectory.depth. The value `default` removes the key (its default applies). A value that is
// not a scalar is written {label: NAME, value: ...}: NAME labels the job (lists, result
// columns), the value (any YAML) is written. Aliases:
//   points levels method offset  -> scene.bodies[role=pointshell].pointshell.<same>
//   resolution                   -> scene.bodies[role=field].field.resolution
//   pointshell_resolution        -> scene.bodies[role=pointshell].field.resolution
//   modes cells                  -> scene.bodies[role=pointshell].deformable.<same>
//   proxies neighbours domains   -> scene.bodies[role=field].deformable.field.<same>
//   max_displacement             -> deformation.max_displacement (deformed-field studies)
//   k_C L node_budget coherence max_point_speed level gradient cold_fraction lipschitz
//                                -> scene.model.<same>
//   model                        -> models (a one-model list)
//   scene                        -> scene (a scene file per job; applied first)
//   roles                        -> normal | swapped: exchanges the bodies' roles (applied
//                                   second, so the other axes act on the final roles)
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"
#include "scene/trajectory.h"
#include "util/config_node.h"

namespace contactlab {

struct SweepAxis {
  std::string name;                 // as written in the config: an alias or a key path
  std::string path;                 // the key path it writes ("" for roles)
  std::vector<std::string> values;  // scalar texts, or the labels of labelled values
  // Per value: what a labelled value {label: NAME, value: ANY} writes (a list or mapping, e.g.
  // explicit domains), as YAML text; empty for a scalar value, which writes its text. (Text, not
  // YAML::Node: assigning a yaml-cpp node writes through to every copy of it.)
  std::vector<std::string> labelled_yaml;
};

struct ExperimentConfig {
  std::string name;
  std::string description;
  std::string file;
  std::string study = "contact";  // contact | deformed-field
  std::string resolved_yaml;   // the config after --set overrides, as YAML text
  YAML::Node document;         // the config after --set overrides
  YAML::Node scene_document;   // the scene's document (the file's, or the inline mapping)
  std::string scene_file;      // where the scene was read from (error messages)
  // The texts DOCUMENT and a scene file's SCENE_DOCUMENT were parsed from (empty: unknown, or an
  // inline scene): each job parses its own copy from them, keeping every key's line for errors.
  std::string document_text;
  std::string scene_text;
  Scene scene;                 // the scene without sweep values
  std::vector<std::string> models;
  std::string moving_body;     // body name
  bool moving_body_is_default = true;  // not given: each job's field body
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
  bool roles_swapped = false;  // the roles axis exchanged the bodies' roles
  ConfigNode trajectory_node;  // the job's trajectory section (contact studies), for errors
  // That section parsed, once per job (ParseTrajectorySpec); empty when the config has none
  // (a study that moves a body requires it: Study::required).
  std::optional<TrajectorySpec> trajectory;
  ConfigNode config;           // the job's whole config document, sweep values applied
  std::string Label() const;  // "points=1024 model=vps"
};

// Reads CONFIG_FILE, applies OVERRIDES ("key.path=value", value parsed as YAML) and checks
// every key. Throws Error naming the file (or the override) and the key.
// PROFILE (may be empty) names an entry of the config's "profiles" whose overrides apply
// before OVERRIDES.
ExperimentConfig LoadExperimentConfig(const std::filesystem::path& config_file,
                                      const std::vector<std::string>& overrides = {},
                                      const std::string& profile = "");
// DOCUMENT_TEXT: the text ROOT was parsed from, when known (each job is parsed from it again,
// keeping its keys' lines for errors).
ExperimentConfig ParseExperimentConfig(const ConfigNode& root, std::string resolved_yaml,
                                       std::string document_text = "");

// The most jobs a sweep may have (the product of its axes' lengths). A config over it is
// refused when it loads, before any job is built: every job is parsed and checked at load.
inline constexpr std::size_t kMaxSweepJobs = 10000;

// The number of jobs of CONFIG's sweep (1 without a sweep); at most kMaxSweepJobs.
std::size_t JobCount(const ExperimentConfig& config);

// Job INDEX (0 <= INDEX < JobCount) of the sweep, built alone. Throws Error naming the config
// file, the job and its values when its combination does not parse.
Job ExpandJob(const ExperimentConfig& config, std::size_t index);

// Job INDEX's label ("points=1024 model=vps", as Job::Label), without building the job.
std::string JobLabel(const ExperimentConfig& config, std::size_t index);

// Calls VISIT with every job in order, each built as it is visited and dropped after it (so a
// check of every job holds one at a time). Throws as ExpandJob does.
void ForEachJob(const ExperimentConfig& config, const std::function<void(const Job&)>& visit);

// The cartesian product of the sweep axes, in order (the last axis varies fastest). Throws
// Error naming the config file, the job and its values when a combination does not parse.
std::vector<Job> ExpandJobs(const ExperimentConfig& config);

// The job with JOB's sweep values but the bodies in the config's roles: JOB itself when its
// roles were not swapped, the roles axis's "normal" job otherwise (none when that axis has no
// "normal" value). Runs of both role orders take their touch placement from it, so they follow
// one motion.
std::optional<Job> ConfigRoleOrderJob(const ExperimentConfig& config, const Job& job);

// Sets DOC at PATH (dot-separated keys; "key[N]", "key[field=value]" pick a list element) to
// VALUE (a YAML node), creating mappings along the way; no VALUE (nullopt) removes the key. Throws
// Error("WHERE: ...") when the path runs into a value that is not a mapping or a list
// element that does not exist.
void SetAtPath(YAML::Node doc, const std::string& path, const std::optional<YAML::Node>& value,
               const std::string& where);

}  // namespace contactlab
