// Shared helpers of the deformable-contact tests: cached assets in a temporary folder, running
// every job of an experiment config, and random deformations of a given size.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <vector>

#include "deform/reduced_model.h"
#include "reduced/reduced_state.h"
#include "experiment/experiment_config.h"
#include "experiment/studies/contact/contact_study.h"
#include "scene/scene_assets.h"
#include "test_support.h"

namespace contactlab::testing {

// Assets cached under DIR/cache, quietly.
inline AssetOptions Assets(const TempDir& dir) {
  AssetOptions o;
  o.cache_dir = dir / "cache";
  o.verbose = false;
  return o;
}

// Runs every job of the experiment config DIR/run.yaml (its scene beside it), caching in DIR.
inline std::vector<JobResult> RunAllJobs(const TempDir& dir) {
  const ExperimentConfig config = LoadExperimentConfig(dir / "run.yaml");
  RunOptions options;
  options.assets = Assets(dir);
  options.progress = false;
  std::vector<JobResult> results;
  for (const Job& job : ExpandJobs(config)) results.push_back(RunJob(config, job, options));
  return results;
}

// A random deformation whose largest displacement of a simulation-mesh vertex is AMPLITUDE metres.
inline ReducedState RandomState(const ReducedModel& model, double amplitude, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  ReducedState s(model.r());
  for (int j = 0; j < model.r(); ++j) s.q[j] = normal(*rng);
  const Eigen::VectorXd u = model.basis * Eigen::VectorXd(s.q);
  double max_u = 0;
  for (Eigen::Index v = 0; v < u.size(); v += 3) max_u = std::max(max_u, u.segment<3>(v).norm());
  s.q *= amplitude / max_u;
  return s;
}

}  // namespace contactlab::testing
