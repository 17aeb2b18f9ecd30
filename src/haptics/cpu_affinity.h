// CPU affinity for a haptic session (`--cpu N`): the real-time loop thread alone on core N,
// every other thread of the session (logger, viewer, watchdog, device input) on the other
// cores the process may use. A thread inherits its creator's mask, so a session takes its main
// thread off N before it starts any other thread, and the loop thread pins itself to N.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace contactlab {

// The CPUs the calling thread may run on (its affinity mask), ascending.
std::vector<int> CpusOfThisThread();

// The number of CPUs the system has configured (sysconf(_SC_NPROCESSORS_CONF)), at least 1.
int ConfiguredCpuCount();

// TEXT as the loop's CPU given as option OPTION (e.g. "--cpu"): an integer in
// [0, ConfiguredCpuCount()) that the calling thread may run on and that leaves it another CPU
// for the session's other threads. Throws Error naming OPTION and what is wrong otherwise.
// Call it before the calling thread's mask is changed.
int ParseLoopCpu(std::string_view text, std::string_view option);

// Pins the calling thread to CPU alone. Returns 0, or the errno of pthread_setaffinity_np
// (EINVAL when CPU is out of range or not allowed). Never throws.
int PinThisThreadToCpu(int cpu) noexcept;

// Removes CPU from the calling thread's mask (threads it starts afterwards inherit that).
// Returns 0 (also when CPU was not in the mask), EINVAL when CPU is the only CPU in the mask,
// or the errno of pthread_getaffinity_np / pthread_setaffinity_np. Never throws.
int KeepThisThreadOffCpu(int cpu) noexcept;

// "0-3,6": CPUS (ascending) as ranges, for messages.
std::string FormatCpuList(const std::vector<int>& cpus);

}  // namespace contactlab
