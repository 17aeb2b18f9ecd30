// The closed-loop study (`study: closed-loop` in an experiment config; Barbič & James 2008,
// sec. 5): per job, each model of the job renders the scene in the simulated haptic loop
// (experiment/studies/closed_loop/closed_loop_stability.h: a simulated hand drives the field
// body through static virtual coupling with quasi-static damping and the safety filter, at the
// scene's rate, 1 / model.cycle_seconds, in simulated time) for each motion of the `loop` section, and the passivity and settling of
// the loop are measured. Sweeping k_vc finds the largest coupling stiffness each model renders stably;
// sweeping cycle_seconds too, how that stiffness changes with the haptic rate.
//
//   study: closed-loop
//   scene: scenes/knight-screwdriver.yaml
//   models: [pointshell, vps, fcl]
//   loop: {k_vc: 1000, motions: [push, slide, corner]}   # the keys: contactlab params
//   sweep: {k_vc: [400, 1000, 2000, 5000]}
//
// Output: stability.csv, one row per job, model and motion (with meta.json).
#pragma once

#include <string>
#include <vector>

#include "experiment/studies/closed_loop/closed_loop_stability.h"
#include "experiment/experiment_config.h"
#include "util/param_table.h"

namespace contactlab {

struct RunOptions;

// The `loop` section: the case every motion starts from, and the motions run.
struct LoopSpec {
  ClosedLoopCase loop;
  std::vector<LoopMotion> motions = {LoopMotion::kPush, LoopMotion::kSlide, LoopMotion::kCorner};
};

const ParamTable<LoopSpec>& LoopParams();

// Reads the `loop` section of a job's config document ROOT (defaults when absent). Throws Error
// naming the file, line and key.
LoopSpec ParseLoopSpec(const ConfigNode& root);

struct LoopRow {
  std::string model;
  LoopMotion motion = LoopMotion::kPush;
  ClosedLoopCase loop;
  ClosedLoopMetrics metrics;
  double wrench_scale = 1;  // model.stiffness: matched's factor on the model's wrench (1: own)
};

struct LoopJobResult {
  Job job;
  std::vector<LoopRow> rows;  // per model, per motion
};

// Runs JOB of a closed-loop config: every model of the job, every motion of its loop section.
LoopJobResult RunClosedLoopJob(const Job& job, const RunOptions& options);

// stability.csv: experiment, job, the sweep axes, then the declared columns.
std::string StabilityCsv(const ExperimentConfig& config, const std::vector<LoopJobResult>& results);

}  // namespace contactlab
