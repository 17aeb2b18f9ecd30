// The many-bodies study (`study: many-bodies`): a scene of many bodies (docs/scenes.md, "Many
// bodies") run as the live session runs it, offline. Per job and model (the model of every pair
// without one of its own), the tool follows the trajectory cycle by cycle through the scene's
// world (scene/scene_world.h): the broad phase, every near pair's model under the cycle's one
// budget, and each deformable body stepped once per cycle with the forces of all its pairs.
//
//   study: many-bodies
//   scene: scenes/hoses-part.yaml     # a scene of many bodies (tool:)
//   models: [pointshell]              # default: the scene's; one run of the trajectory each
//   trajectory: {type: slide, direction: [0, 0, -1], depth: 0.0005, tangent: [1, 0, 0], length: 0.05}
//
// The trajectory moves the tool from its scene pose (a vector direction; `direction: toward` and
// `touch: true` need two bodies). Outputs: world_cycles.csv (the totals, one row per cycle per
// model), world_pairs.csv (one row per near pair per cycle: its model's result), world_bodies.csv
// (one row per deformable body per cycle) and world_summary.csv (one row per model per job),
// written atomically with meta.json.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "experiment/experiment_config.h"
#include "experiment/runner.h"

namespace contactlab {

// The totals of one cycle of one model's run.
struct WorldCycleRow {
  int model = 0;                 // index into WorldJobResult::models
  std::int64_t cycle = 0;
  double t = 0;                  // s
  Eigen::Vector3d position = Eigen::Vector3d::Zero();            // the tool's origin, world
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // the tool's orientation, world
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // on the tool, world, N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // on the tool about its origin, N m
  int pairs_near = 0, pairs_touching = 0, pairs_degraded = 0, faults = 0;
  int beyond_bound = 0;  // deformable bodies displaced past their deformation bound
  int contacts = 0;
  std::int64_t nodes = 0;
  double max_penetration = 0;    // m, over the pairs
  double time_us = 0;            // the world's cycle: broad phase, pairs, deformable steps
  bool coherence_reset = false;  // the tool outran max_point_speed: every pair's coherence forgotten
};

// One near pair in one cycle: its model's result, on the pair's B.
struct WorldPairRow {
  int model = 0;
  std::int64_t cycle = 0;
  double t = 0;
  int pair = 0;                  // index into the scene's pairs
  std::int64_t budget = 0;       // the node budget it was handed (0: unlimited)
  int contacts = 0;
  std::int64_t nodes = 0;
  int level = -1;
  int degraded = 0;
  double max_penetration = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // on B, world, N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // on B about its origin, world, N m
};

// One deformable body after one cycle's step.
struct WorldBodyRow {
  int model = 0;
  std::int64_t cycle = 0;
  double t = 0;
  int body = 0;                  // index into Scene::bodies
  double max_displacement = 0;   // m, largest |U q| over its simulation mesh's vertices
  double elastic_energy = 0, kinetic_energy = 0;  // J (mass-normalised coordinates)
  std::vector<double> q;         // its reduced coordinates after the step (the replay deforms it)
};

// One model's run of one job.
struct WorldSummaryRow {
  int model = 0;
  int bodies = 0, pairs = 0, deformable = 0;
  std::int64_t cycles = 0;
  double median_us = 0, p99_us = 0, p999_us = 0, max_us = 0;
  double mean_pairs_near = 0;
  int max_pairs_touching = 0;
  double touching_share = 0;     // of the cycles, those with some pair in contact
  double degraded_share = 0;     // of the cycles, those in which some pair degraded
  double max_force = 0;          // N, |force on the tool|
  std::int64_t faults = 0, coherence_resets = 0;
  std::int64_t beyond_bound_cycles = 0;  // cycles some deformable body was past its deformation bound
  double max_displacement = 0;   // m, over the deformable bodies and the cycles
};

// A pair as the tables name it: its bodies in its model's A/B order and its model.
struct WorldPairName {
  std::string body_A, body_B, model;
};

struct WorldJobResult {
  Job job;
  std::vector<std::string> models;     // the job's models, the default of each run
  std::vector<WorldPairName> pairs;    // per model run, the scene's pairs: models.size() x pairs
  std::vector<WorldCycleRow> cycles;
  std::vector<WorldPairRow> pair_rows;
  std::vector<WorldBodyRow> body_rows;
  std::vector<WorldSummaryRow> summary;
};

// Runs JOB of a many-bodies config (assets built or reused through OPTIONS.assets); the config's
// parse has checked the job (a scene of many bodies, a trajectory from the tool's pose).
WorldJobResult RunWorldJob(const Job& job, const RunOptions& options);

// Runs JOBS (all when empty), one at a time unless OPTIONS says otherwise (the study measures
// cycle times), and writes its tables and meta.json into OPTIONS.out_dir. Returns each job's
// result. The study registers as `many-bodies` (experiment/study.h).
std::vector<WorldJobResult> RunWorldStudy(const ExperimentConfig& config, const RunOptions& options,
                                          const std::vector<int>& jobs = {});

}  // namespace contactlab
