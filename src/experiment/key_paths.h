// Key paths of experiment configs (key_paths.cc; internal to the experiment library: SetAtPath
// in experiment_config.h is the interface).
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

namespace contactlab {

// Sets ROOT[path] = VALUE from ASSIGNMENT ("key.path=value", the value YAML text; "sweep.AXIS"
// names one key of the sweep mapping), creating maps along the path: --set and profiles.
// Throws Error naming the assignment and FILE.
void ApplyOverride(YAML::Node root, const std::string& assignment, const std::string& file);

}  // namespace contactlab
