// The real-time haptic loop (Barbič & James 2008, sec. 5: one haptic cycle per millisecond; here
// any rate up to 100 kHz, a session's from its scene's model.cycle_seconds): absolute deadlines, SCHED_FIFO and mlockall when permitted, a cycle-time
// histogram, deadline-miss counting with a skip-ahead catch-up policy, a watchdog thread, a
// lock-free ring of cycle records for a graphics or logging consumer, and a clean stop on
// SIGINT (also SIGTERM, SIGHUP, SIGQUIT) that leaves the device at zero force. Each cycle's thread CPU time is measured beside
// its wall time, so that a deadline miss has a cause (deadline_miss.h: overrun or preempted)
// and the largest ten are kept. Optionally the loop thread runs pinned to one core
// (cpu_affinity.h). Its time comes from a LoopClock: the monotonic clock in a session,
// simulated time in tests.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "contact/contact_params.h"
#include "haptics/deadline_miss.h"
#include "haptics/haptic_cycle.h"
#include "haptics/spsc_ring.h"
#include "haptics/timing_histogram.h"

namespace contactlab {

// Longest run a loop is given (HapticLoopOptions::duration_seconds, `session --duration`): about
// three years, far inside the int64 nanoseconds of the loop's clock (292 years).
inline constexpr double kMaxLoopSeconds = 1e8;

// The rates a loop runs at: those of the cycles a scene may ask for (contact/contact_params.h),
// 10 Hz to 100 kHz.
inline constexpr double kMinLoopRateHz = 1.0 / kMaxCycleSeconds;
inline constexpr double kMaxLoopRateHz = 1.0 / kMinCycleSeconds;

// The longest the loop waits without looking at its stop flag, the stop signals and its end
// time: a wait for a release further off is taken in slices of this length.
inline constexpr std::int64_t kLoopWaitSliceNs = 5'000'000;

struct HapticLoopOptions {
  double rate_hz = 1000;              // cycle rate, in [kMinLoopRateHz, kMaxLoopRateHz]
  double duration_seconds = 0;        // run time, at most kMaxLoopSeconds; <= 0 runs until RequestStop or SIGINT
  bool try_realtime = true;           // try SCHED_FIFO + mlockall (warn on stderr if refused)
  int fifo_priority = 80;             // SCHED_FIFO priority when granted
  double spin_seconds = 50e-6;        // sleep until this long before the deadline, then spin (< 1/rate_hz;
                                      // LoopSpinSeconds gives one for any rate)
  double watchdog_seconds = 0.01;     // watchdog thread zeroes the device if the loop stalls this long; <= 0 disables
  bool honour_sigint = true;          // stop when a stop signal arrived (SIGINT, TERM, HUP, QUIT)
  // Core the loop thread pins itself to (pthread_setaffinity_np); -1: not pinned. The watchdog
  // thread takes itself off it. Keeping the caller's other threads off it is the caller's
  // part (KeepThisThreadOffCpu before it starts them; the session's --cpu does).
  int cpu = -1;
};

struct HapticLoopReport {
  std::int64_t cycles = 0;            // cycles run
  std::int64_t deadline_misses = 0;   // cycles that finished after the next cycle's release
  std::int64_t misses_overrun = 0;    // of which the work's thread CPU time exceeded the period
  std::int64_t misses_preempted = 0;  // of which it did not: the thread was not running
  std::int64_t period_ns = 0;         // the loop's period
  double rate_hz = 0;                 // the loop's rate (1e9 / period_ns)
  std::int64_t spin_ns = 0;           // how long before each release the loop stops sleeping and spins
  std::int64_t run_ns = 0;            // wall time from the first release to the stop
  std::int64_t loop_cpu_ns = 0;       // the loop thread's CPU time over run_ns: work plus waiting
  std::int64_t work_cpu_ns = 0;       // of which the cycles' work (the sum of the cpu histogram's samples)
  std::int64_t skipped_cycles = 0;    // releases skipped by the catch-up policy
  std::int64_t watchdog_zeroes = 0;   // times the watchdog thread zeroed the device
  bool realtime_scheduling = false;   // SCHED_FIFO granted
  bool memory_locked = false;         // mlockall granted
  bool stopped_by_signal = false;
  int pinned_cpu = -1;                // the core the loop thread ran pinned to; -1: not pinned
  TimingHistogram work;               // time from the cycle's start to the wrench being written
  TimingHistogram cpu;                // the loop thread's CPU time over that work
  TimingHistogram wake_latency;       // lateness of the wake-up after the release time
  TimingHistogram period;             // time between consecutive cycle starts
  SafetyStats safety;                 // the cycle's safety counters at the end
  std::int64_t coherence_resets = 0;  // cycles where H outran max_point_speed (model reset)
  std::int64_t contact_faults = 0;    // cycles whose contact query the model refused (no force)
  DeviceInputStats device_input;      // the device's input counters at the end (udp rejections)
  LargestMisses largest_misses;       // the ten largest misses by wall time from release
};

// Cycle records for consumers; the loop drops records (counted) when the consumer lags.
using CycleRing = SpscRing<CycleRecord, 1024>;

// Where the loop and its watchdog read the time and how they wait for it. The loop thread
// calls NowNs and WaitUntil, the watchdog thread NowNs and Sleep, concurrently: an
// implementation must be thread-safe. MonotonicLoopClock() is the real one; a test passes a
// simulated clock so that cycles, misses and stalls happen in exact simulated time whatever
// the scheduler does.
class LoopClock {
 public:
  virtual ~LoopClock() = default;
  // Nanoseconds on a monotonic time line (any origin).
  virtual std::int64_t NowNs() = 0;
  // Returns once NowNs() >= DEADLINE_NS. A real clock sleeps until SPIN_NS before the
  // deadline, then spins.
  virtual void WaitUntil(std::int64_t deadline_ns, std::int64_t spin_ns) = 0;
  // Waits about DURATION_NS (the watchdog's poll); may return early.
  virtual void Sleep(std::int64_t duration_ns) = 0;
  // CPU time the calling thread (the loop thread) has used, ns; only differences count. The
  // default reads CLOCK_THREAD_CPUTIME_ID (a vDSO call: no lock, no allocation); a simulated
  // clock counts simulated work.
  virtual std::int64_t ThreadCpuNs();
};

// CLOCK_MONOTONIC with absolute-time sleeps: the clock of every real session.
LoopClock& MonotonicLoopClock();

class HapticLoop {
 public:
  // CYCLE and CLOCK must outlive the loop. Throws Error when OPTIONS is invalid.
  HapticLoop(HapticCycle& cycle, const HapticLoopOptions& options, LoopClock& clock = MonotonicLoopClock());
  ~HapticLoop();  // stops and joins

  // Starts the loop thread (throws Error if already running or the thread cannot start).
  void Start();
  // Asks the loop to stop; it exits after the current cycle and writes a zero wrench.
  void RequestStop() { stop_.store(true, std::memory_order_relaxed); }
  // Waits for the loop thread and returns its report.
  HapticLoopReport Join();
  // Start + Join on the calling thread's behalf.
  HapticLoopReport Run() {
    Start();
    return Join();
  }

  // Consumer side of the record ring (one consumer thread).
  CycleRing& records() { return ring_; }
  bool running() const { return running_.load(std::memory_order_acquire); }

 private:
  void ThreadMain();
  void WatchdogMain();

  HapticCycle& cycle_;
  HapticLoopOptions options_;
  LoopClock& clock_;
  CycleRing ring_;
  HapticLoopReport report_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> running_{false};
  std::atomic<std::int64_t> heartbeat_ns_{0};
  std::atomic<std::int64_t> watchdog_zeroes_{0};
  std::thread thread_;
  std::thread watchdog_;
};

// The loop's period for RATE_HZ, nanoseconds to the nearest (the loop runs at 1e9 / period).
std::int64_t LoopPeriodNs(double rate_hz);

// How long before a release a loop at RATE_HZ stops sleeping and spins: 50 us (the wake-up
// latency of an absolute-time sleep on a stock kernel is tens of microseconds), at most half
// the period, so that from 10 kHz the loop sleeps for half of each period and spins for the
// other half.
double LoopSpinSeconds(double rate_hz);

// The loop rate of a haptic cycle of CYCLE_SECONDS (a scene's model.cycle_seconds): 1 /
// CYCLE_SECONDS. Throws Error naming WHERE when the rate does not lie in [10 Hz, 100 kHz].
double LoopRateOfCycle(double cycle_seconds, const std::string& where);

// Monotonic clock (CLOCK_MONOTONIC), nanoseconds.
std::int64_t MonotonicNowNs();

// Installs SIGINT, SIGTERM, SIGHUP and SIGQUIT handlers that only set an atomic flag
// (async-signal-safe), so that any of them stops the loop as cleanly as Ctrl-C.
void InstallStopSignalHandlers();
// True once one of those signals arrived after InstallStopSignalHandlers.
bool StopSignalRequested();
// Clears the flag (tests, or a new session).
void ClearStopSignal();

// "received N, accepted N, rejected N (malformed, duplicate, out of order, stale, future),
// resyncs N": the input counters of a device that can reject samples.
std::string FormatDeviceInputStats(const DeviceInputStats& s);

// The table of MISSES (largest first), one row each: cycle, time into the session, wall time
// from release, wake-up lateness, work, work CPU time (us), nodes, contacts, level, step time,
// cause; PERIOD_NS is the loop's period (the rule's threshold, printed in the title).
std::string FormatLargestMisses(const LargestMisses& misses, std::int64_t period_ns);

// One histogram's line of the report: "  NAME us: p50 A  p99 B  p99.9 C  max D  (n N)", and when
// samples exceed the 1 us bins "; over 5000 us: K, resolved to 1.1 %" (and past the histogram's
// range "; over L us: K, not resolved", a percentile there printed as ">L").
std::string FormatTimingHistogram(const char* name, const TimingHistogram& histogram);

// A human-readable summary of REPORT (percentiles in microseconds): cycles, misses split into
// overrun and preempted (deadline_miss.h), the timing histograms, the safety counters and the
// table of the largest misses.
std::string FormatLoopReport(const HapticLoopReport& report);

}  // namespace contactlab
