// meta.json of an experiment run: the resolved config, the jobs run, wall time, and what a
// reader needs to reproduce the numbers (commit, compiler and flags, library versions, CPU,
// host, time).
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "experiment/experiment_config.h"

namespace contactlab {

nlohmann::json RunMetadata(const ExperimentConfig& config, const std::vector<int>& jobs, double wall_seconds,
                           int parallel_jobs);

}  // namespace contactlab
