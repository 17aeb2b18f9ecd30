#include "experiment/run_metadata.h"

#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>

namespace contactlab {
namespace {

std::string CommandOutput(const std::string& command) {
  std::string out;
  if (FILE* p = ::popen(command.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    ::pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

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
  j["description"] = config.description;
  j["config_file"] = config.file;
  j["resolved_config"] = config.resolved_yaml;
  j["jobs"] = jobs;
  j["parallel_jobs"] = parallel;
  j["wall_seconds"] = wall_seconds;
  std::string commit = CommandOutput(std::string("git -C '") + CONTACTLAB_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null");
  if (commit.empty()) commit = "unknown";
  if (!CommandOutput(std::string("git -C '") + CONTACTLAB_SOURCE_DIR + "' status --porcelain --untracked-files=no 2>/dev/null").empty()) {
    commit += " (with uncommitted changes)";
  }
  j["git_commit"] = commit;
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
