#include "experiment/run_metadata.h"

#include "experiment/source_revision.h"

#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>

namespace contactlab {
namespace {

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

}  // namespace

nlohmann::json RunMetadata(const ExperimentConfig& config, const std::vector<int>& jobs, double wall_seconds,
                           int parallel) {
  nlohmann::json j;
  j["experiment"] = config.name;
  j["study"] = config.study;
  j["description"] = config.description;
  j["config_file"] = config.file;
  j["resolved_config"] = config.resolved_yaml;
  j["jobs"] = jobs;
  j["sweep_jobs"] = JobCount(config);  // all of the sweep's jobs, for a merge to check
  j["parallel_jobs"] = parallel;
  j["wall_seconds"] = wall_seconds;
  j["git_commit"] = ConfigRevision(config.file);  // the checkout holding the config
  j["build_commit"] = BuildRevision();             // the checkout the binary was built from
  j["contactlab_version"] = CONTACTLAB_VERSION;
  j["compiler"] = CONTACTLAB_COMPILER;
  j["compiler_flags"] = CONTACTLAB_CXX_FLAGS;
  j["build_type"] = CONTACTLAB_BUILD_TYPE;
  j["library_versions"] = CONTACTLAB_LIBRARY_VERSIONS;
  j["cpu"] = CpuModel();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  j["host"] = host;
  const std::time_t now = std::time(nullptr);
  char stamp[64];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["finished_utc"] = stamp;
  return j;
}

}  // namespace contactlab
