// CPU affinity for a haptic session (`--cpu N`).
#include "haptics/cpu_affinity.h"

#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <optional>

#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {

std::vector<int> CpusOfThisThread() {
  std::vector<int> cpus;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (pthread_getaffinity_np(pthread_self(), sizeof(set), &set) != 0) return cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  return cpus;
}

int ConfiguredCpuCount() {
  const long n = sysconf(_SC_NPROCESSORS_CONF);
  return n >= 1 ? int(std::min<long>(n, CPU_SETSIZE)) : 1;
}

std::string FormatCpuList(const std::vector<int>& cpus) {
  std::string s;
  for (std::size_t i = 0; i < cpus.size();) {
    std::size_t j = i;
    while (j + 1 < cpus.size() && cpus[j + 1] == cpus[j] + 1) ++j;
    if (!s.empty()) s += ",";
    s += std::to_string(cpus[i]);
    if (j > i) {
      s += '-';
      s += std::to_string(cpus[j]);
    }
    i = j + 1;
  }
  return s.empty() ? "none" : s;
}

int ParseLoopCpu(std::string_view text, std::string_view option) {
  const int count = ConfiguredCpuCount();
  const std::string range = "0.." + std::to_string(count - 1);
  const std::optional<long long> n = ParseInteger(text);
  if (!n) Fail(option, QuoteToken(text) + " is not a CPU number (this machine has " + std::to_string(count) +
                           " CPUs: " + range + ")");
  if (*n < 0 || *n >= count)
    Fail(option, "CPU " + std::to_string(*n) + " does not exist (this machine has " + std::to_string(count) +
                     " CPUs: " + range + ")");
  const int cpu = int(*n);
  const std::vector<int> allowed = CpusOfThisThread();
  if (std::find(allowed.begin(), allowed.end(), cpu) == allowed.end())
    Fail(option, "CPU " + std::to_string(cpu) + " is not among the CPUs this process may run on (" +
                     FormatCpuList(allowed) + "; see taskset, cgroup cpusets)");
  if (allowed.size() < 2)
    Fail(option, "CPU " + std::to_string(cpu) +
                     " is the only CPU this process may run on; the session's other threads need another");
  return cpu;
}

int PinThisThreadToCpu(int cpu) noexcept {
  if (cpu < 0 || cpu >= CPU_SETSIZE) return EINVAL;
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
}

int KeepThisThreadOffCpu(int cpu) noexcept {
  if (cpu < 0 || cpu >= CPU_SETSIZE) return EINVAL;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (const int err = pthread_getaffinity_np(pthread_self(), sizeof(set), &set); err != 0) return err;
  if (!CPU_ISSET(cpu, &set)) return 0;
  CPU_CLR(cpu, &set);
  if (CPU_COUNT(&set) == 0) return EINVAL;
  return pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
}

}  // namespace contactlab
