// The steps of expanding an experiment config into its jobs that its parser shares
// (job_expansion.cc; internal to the experiment library, whose interface is
// experiment_config.h).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "experiment/experiment_config.h"

namespace contactlab {

// The documents one job is parsed from.
struct JobDocuments {
  YAML::Node config;
  YAML::Node scene;
  std::string scene_file;
  std::string scene_text;  // the scene file's text (empty: an inline scene)
  bool roles_swapped = false;
};

// Loads the scene file NAME (data search path, first from the folder of CONFIG_FILE) as a
// document into DOCS.
void LoadSceneDocument(const std::string& name, const std::string& config_file, JobDocuments* docs);

// Builds job INDEX of CONFIG with the axis values PICK (one index per axis) from CONFIG's
// documents. Throws Error naming the config and the key.
Job BuildJob(const ExperimentConfig& config, int index, const std::vector<std::size_t>& pick);

}  // namespace contactlab
