// The real-time haptic loop (Barbič & James 2008, sec. 5).
#include "haptics/haptic_loop.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <optional>
#include <sstream>

#include "haptics/cpu_affinity.h"
#include "haptics/udp_device.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::atomic<bool> g_stop_signal{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal flag must be lock-free");

extern "C" void OnStopSignal(int) { g_stop_signal.store(true, std::memory_order_relaxed); }

timespec ToTimespec(std::int64_t ns) {
  timespec ts;
  ts.tv_sec = time_t(ns / 1000000000);
  ts.tv_nsec = long(ns % 1000000000);
  return ts;
}

class MonotonicClock final : public LoopClock {
 public:
  std::int64_t NowNs() override { return MonotonicNowNs(); }
  // Sleeps to SPIN_NS before DEADLINE_NS with an absolute-time sleep, then spins.
  void WaitUntil(std::int64_t deadline_ns, std::int64_t spin_ns) override {
    const std::int64_t wake = deadline_ns - spin_ns;
    if (MonotonicNowNs() < wake) {
      const timespec ts = ToTimespec(wake);
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
      }
    }
    while (MonotonicNowNs() < deadline_ns) {
    }
  }
  void Sleep(std::int64_t duration_ns) override {
    const timespec ts = ToTimespec(duration_ns);
    nanosleep(&ts, nullptr);
  }
};

}  // namespace

std::int64_t LoopClock::ThreadCpuNs() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

LoopClock& MonotonicLoopClock() {
  static MonotonicClock clock;
  return clock;
}

std::int64_t LoopPeriodNs(double rate_hz) { return std::max<std::int64_t>(1, std::llround(1e9 / rate_hz)); }

double LoopSpinSeconds(double rate_hz) { return std::min(50e-6, 0.5 / rate_hz); }

double LoopRateOfCycle(double cycle_seconds, const std::string& where) {
  if (!(std::isfinite(cycle_seconds) && cycle_seconds >= kMinCycleSeconds && cycle_seconds <= kMaxCycleSeconds)) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", cycle_seconds);
    Fail(where, std::string("a haptic cycle of ") + text +
                    " s gives no loop rate in [10 Hz, 100 kHz]: cycle_seconds must lie in [1e-5, 0.1] s");
  }
  return 1.0 / cycle_seconds;
}

std::int64_t MonotonicNowNs() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

void InstallStopSignalHandlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  // Every signal that asks a terminal program to stop: Ctrl-C, kill, a closed terminal, Ctrl-\.
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaction(signal_number, &sa, nullptr);
}

bool StopSignalRequested() { return g_stop_signal.load(std::memory_order_relaxed); }
void ClearStopSignal() { g_stop_signal.store(false, std::memory_order_relaxed); }

HapticLoop::HapticLoop(HapticCycle& cycle, const HapticLoopOptions& options, LoopClock& clock)
    : cycle_(cycle), options_(options), clock_(clock) {
  if (!(options_.rate_hz >= kMinLoopRateHz && options_.rate_hz <= kMaxLoopRateHz))
    Fail("haptic loop", "rate_hz must lie in [10, 100000]");
  if (!(options_.spin_seconds >= 0 && options_.spin_seconds < 1.0 / options_.rate_hz))
    Fail("haptic loop", "spin_seconds must lie in [0, 1/rate_hz)");
  // NaN compares false with everything: without this check it would run forever ("<= 0"
  // is false too), and a huge duration would overflow the clock's nanoseconds.
  if (!std::isfinite(options_.duration_seconds) || options_.duration_seconds > kMaxLoopSeconds)
    Fail("haptic loop", "duration_seconds must be a finite number of seconds, at most 1e8 (<= 0: until stopped)");
  if (options_.fifo_priority < 1 || options_.fifo_priority > 99) Fail("haptic loop", "fifo_priority must lie in [1, 99]");
  if (options_.cpu < -1 || options_.cpu >= ConfiguredCpuCount())
    Fail("haptic loop", "cpu must be -1 (not pinned) or a CPU of this machine (0.." +
                            std::to_string(ConfiguredCpuCount() - 1) + ")");
}

HapticLoop::~HapticLoop() {
  RequestStop();
  if (thread_.joinable()) thread_.join();
  if (watchdog_.joinable()) watchdog_.join();
}

void HapticLoop::Start() {
  if (thread_.joinable()) Fail("haptic loop", "already started");
  stop_.store(false);
  report_ = HapticLoopReport{};
  watchdog_zeroes_.store(0);
  running_.store(true, std::memory_order_release);
  heartbeat_ns_.store(0);  // the watchdog arms at the first cycle, after real-time setup
  try {
    thread_ = std::thread([this] { ThreadMain(); });
    if (options_.watchdog_seconds > 0) watchdog_ = std::thread([this] { WatchdogMain(); });
  } catch (const std::system_error& e) {
    running_.store(false);
    Fail("haptic loop", std::string("cannot start thread: ") + e.what());
  }
}

HapticLoopReport HapticLoop::Join() {
  if (thread_.joinable()) thread_.join();
  if (watchdog_.joinable()) watchdog_.join();
  report_.watchdog_zeroes = watchdog_zeroes_.load();
  report_.safety = cycle_.safety().stats();
  report_.coherence_resets = cycle_.coherence_resets();
  report_.contact_faults = cycle_.contact_faults();
  report_.device_input = cycle_.device().input_stats();
  return report_;
}

void HapticLoop::WatchdogMain() {
  // Off the loop's core, when it has one: the core is the loop thread's alone.
  if (options_.cpu >= 0) {
    if (const int err = KeepThisThreadOffCpu(options_.cpu); err != 0)
      std::fprintf(stderr, "warning: haptic loop: watchdog cannot leave CPU %d (%s)\n", options_.cpu, std::strerror(err));
  }
  // Polls the loop's heartbeat every 1 ms; a stale heartbeat zeroes the device once per stall.
  const std::int64_t limit = std::int64_t(options_.watchdog_seconds * 1e9);
  bool tripped = false;
  while (running_.load(std::memory_order_acquire)) {
    clock_.Sleep(1000000);
    // The time before the heartbeat: a loop that beats between the two reads makes the age
    // smaller, never larger, so a watchdog preempted here cannot see a stall that was not.
    const std::int64_t now = clock_.NowNs();
    const std::int64_t beat = heartbeat_ns_.load();
    if (beat == 0) continue;  // not armed yet
    const std::int64_t age = now - beat;
    if (age > limit) {
      if (!tripped) {
        cycle_.device().EmergencyZero();
        watchdog_zeroes_.fetch_add(1, std::memory_order_relaxed);
      }
      tripped = true;
    } else {
      tripped = false;
    }
  }
}

void HapticLoop::ThreadMain() {
  HapticLoopReport& r = report_;
  // Pinning, before the real-time setup (a clear warning and an unpinned thread when refused).
  if (options_.cpu >= 0) {
    const int err = PinThisThreadToCpu(options_.cpu);
    if (err == 0) {
      r.pinned_cpu = options_.cpu;
    } else {
      std::fprintf(stderr, "warning: haptic loop: cannot pin the loop thread to CPU %d (%s); running unpinned\n",
                   options_.cpu, std::strerror(err));
    }
  }
  // Real-time setup, before the loop: a clear warning and a normal thread when refused.
  if (options_.try_realtime) {
    sched_param sp;
    sp.sched_priority = options_.fifo_priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    r.realtime_scheduling = (err == 0);
    if (err != 0)
      std::fprintf(stderr, "warning: haptic loop: SCHED_FIFO priority %d refused (%s); running as a normal thread\n",
                   options_.fifo_priority, std::strerror(err));
    r.memory_locked = (mlockall(MCL_CURRENT | MCL_FUTURE) == 0);
    if (!r.memory_locked)
      std::fprintf(stderr, "warning: haptic loop: mlockall refused (%s); page faults may delay cycles\n",
                   std::strerror(errno));
  }

  const std::int64_t period_ns = LoopPeriodNs(options_.rate_hz);
  r.period_ns = period_ns;
  r.rate_hz = 1e9 / double(period_ns);
  const std::int64_t spin_ns = std::int64_t(options_.spin_seconds * 1e9);
  r.spin_ns = spin_ns;
  const std::int64_t start_ns = clock_.NowNs();
  const std::int64_t start_cpu_ns = clock_.ThreadCpuNs();
  const std::int64_t end_ns =
      options_.duration_seconds > 0 ? start_ns + std::int64_t(options_.duration_seconds * 1e9) : INT64_MAX;
  cycle_.Start(start_ns);
  std::int64_t release = start_ns + period_ns;
  std::int64_t prev_start = -1;

  // The loop: no allocation, no lock, no exception below.
  const auto stop_asked = [&] {
    if (stop_.load(std::memory_order_relaxed)) return true;
    if (options_.honour_sigint && StopSignalRequested()) {
      r.stopped_by_signal = true;
      return true;
    }
    return false;
  };
  for (;;) {
    if (stop_asked()) break;
    // The wait for the release, never past the end time, in slices that look at the stop.
    const std::int64_t until = std::min(release, end_ns);
    bool stopped = false;
    for (std::int64_t now = clock_.NowNs(); until - now > kLoopWaitSliceNs && !stopped; now = clock_.NowNs()) {
      clock_.WaitUntil(now + kLoopWaitSliceNs, 0);
      stopped = stop_asked();
    }
    if (stopped) break;
    clock_.WaitUntil(until, spin_ns);
    const std::int64_t t0 = clock_.NowNs();
    if (t0 >= end_ns) break;
    heartbeat_ns_.store(t0);

    // The work, timed twice: wall time (the loop clock) around the thread's CPU time.
    const std::int64_t c0 = clock_.ThreadCpuNs();
    CycleRecord rec = cycle_.Step(t0);
    const std::int64_t c1 = clock_.ThreadCpuNs();
    const std::int64_t t1 = clock_.NowNs();
    rec.work_ns = t1 - t0;
    rec.cpu_ns = c1 - c0;
    ring_.TryPush(rec);

    r.work.Add(rec.work_ns);
    r.cpu.Add(rec.cpu_ns);
    r.work_cpu_ns += rec.cpu_ns;
    r.wake_latency.Add(t0 - release);
    if (prev_start >= 0) r.period.Add(t0 - prev_start);
    prev_start = t0;
    ++r.cycles;

    // Next release; a cycle that ends after it is a miss, and missed releases are skipped
    // (the deadline jumps past now) instead of being run in a burst. A miss is an overrun when
    // its work's CPU time alone exceeds the period, else preempted (deadline_miss.h).
    const std::int64_t this_release = release;
    release += period_ns;
    if (t1 > release) {
      ++r.deadline_misses;
      const MissCause cause = ClassifyMiss(rec.cpu_ns, period_ns);
      ++(cause == MissCause::kOverrun ? r.misses_overrun : r.misses_preempted);
      r.largest_misses.Offer(MissRecord{.cycle = rec.cycle,
                                        .at_ns = t0 - start_ns,
                                        .wall_ns = t1 - this_release,
                                        .wake_ns = t0 - this_release,
                                        .work_ns = rec.work_ns,
                                        .cpu_ns = rec.cpu_ns,
                                        .nodes_visited = rec.nodes_visited,
                                        .points_in_contact = rec.points_in_contact,
                                        .level_rendered = rec.level_rendered,
                                        .step_ns = rec.step_ns,
                                        .cause = cause});
      const std::int64_t behind = (t1 - release) / period_ns + 1;
      r.skipped_cycles += behind;
      release += behind * period_ns;
    }
  }

  // The loop has ended: the watchdog disarms (heartbeat 0), since the clean stop below zeroes the
  // device itself and what follows it (munlockall of a large process takes tens of ms) is no
  // stall of a cycle.
  heartbeat_ns_.store(0);
  r.run_ns = clock_.NowNs() - start_ns;
  r.loop_cpu_ns = clock_.ThreadCpuNs() - start_cpu_ns;
  // Clean stop: zero wrench, then let the watchdog go.
  cycle_.WriteZero(clock_.NowNs());
  if (r.memory_locked) munlockall();
  running_.store(false, std::memory_order_release);
}

std::string FormatDeviceInputStats(const DeviceInputStats& s) {
  std::ostringstream os;
  os << "received " << s.received << ", accepted " << s.accepted << ", rejected " << s.rejected() << " (malformed "
     << s.malformed << ", duplicate " << s.duplicate << ", out of order " << s.out_of_order << ", stale " << s.stale
     << ", future " << s.future << "), resyncs " << s.resyncs;
  if (s.foreign > 0) {
    os << "; refused " << s.foreign << " from senders not allowed (latest " << Ipv4Text(s.last_foreign_address) << ")";
  }
  return os.str();
}

std::string FormatLargestMisses(const LargestMisses& misses, std::int64_t period_ns) {
  std::ostringstream os;
  os << "  largest misses (wall: release to wrench written; overrun: work cpu > period " << double(period_ns) * 1e-3
     << " us; preempted: not):\n";
  char row[200];
  std::snprintf(row, sizeof row, "  %9s %9s %9s %9s %9s %9s %8s %8s %5s %8s  %s\n", "cycle", "at s", "wall us",
                "wake us", "work us", "cpu us", "nodes", "contacts", "level", "step us", "cause");
  os << row;
  for (const MissRecord& m : misses) {
    std::snprintf(row, sizeof row, "  %9lld %9.3f %9.1f %9.1f %9.1f %9.1f %8lld %8d %5d %8.1f  %s\n",
                  static_cast<long long>(m.cycle), double(m.at_ns) * 1e-9, double(m.wall_ns) * 1e-3,
                  double(m.wake_ns) * 1e-3, double(m.work_ns) * 1e-3, double(m.cpu_ns) * 1e-3,
                  static_cast<long long>(m.nodes_visited), m.points_in_contact, m.level_rendered,
                  double(m.step_ns) * 1e-3, MissCauseName(m.cause));
    os << row;
  }
  return os.str();
}

std::string FormatTimingHistogram(const char* name, const TimingHistogram& h) {
  std::ostringstream os;
  const auto quantile = [&](double q) {
    const std::optional<double> s = h.QuantileSeconds(q);
    std::ostringstream v;
    if (s) {
      v << *s * 1e6;
    } else {
      v << ">" << static_cast<long long>(TimingHistogram::kLimitSeconds * 1e6);
    }
    return v.str();
  };
  os << "  " << name << " us: p50 " << quantile(0.5) << "  p99 " << quantile(0.99) << "  p99.9 " << quantile(0.999)
     << "  max " << h.max_seconds() * 1e6 << "  (n " << h.count();
  // Samples past the 1 us bins are said so: how many, and how finely they are resolved.
  if (h.beyond_fine() > 0) {
    os << "; over " << TimingHistogram::kFineLimitSeconds * 1e6 << " us: " << h.beyond_fine() << ", resolved to "
       << std::setprecision(2) << TimingHistogram::kCoarseRelativeWidth * 100 << std::setprecision(6) << " %";
  }
  if (h.overflow() > 0) {
    os << "; over " << static_cast<long long>(TimingHistogram::kLimitSeconds * 1e6) << " us: " << h.overflow()
       << ", not resolved";
  }
  os << ")\n";
  return os.str();
}

std::string FormatLoopReport(const HapticLoopReport& r) {
  std::ostringstream os;
  // The rate, and what waiting for it costs the loop's core: the loop thread's CPU time over the
  // run, split into the cycles' work and the rest (the sleep's overhead and the spin before
  // each release).
  os << "rate " << r.rate_hz << " Hz (period " << double(r.period_ns) * 1e-3 << " us, spin " << double(r.spin_ns) * 1e-3
     << " us before each release)";
  if (r.run_ns > 0) {
    const double busy = 100.0 * double(r.loop_cpu_ns) / double(r.run_ns);
    const double work = 100.0 * double(r.work_cpu_ns) / double(r.run_ns);
    os << std::fixed << std::setprecision(1) << "; loop thread on its core " << busy << " % of the run: work " << work
       << " %, waiting " << std::max(0.0, busy - work) << " %" << std::defaultfloat << std::setprecision(6);
  }
  os << "\n";
  os << "cycles " << r.cycles << ", deadline misses " << r.deadline_misses << " (overrun " << r.misses_overrun
     << ", preempted " << r.misses_preempted << "), skipped " << r.skipped_cycles << ", watchdog zeroes "
     << r.watchdog_zeroes << (r.realtime_scheduling ? ", SCHED_FIFO" : ", normal scheduling")
     << (r.memory_locked ? ", mlocked" : ", not mlocked");
  if (r.pinned_cpu >= 0) os << ", pinned to CPU " << r.pinned_cpu;
  os << (r.stopped_by_signal ? ", stopped by signal" : "") << "\n";
  os << FormatTimingHistogram("work        ", r.work) << FormatTimingHistogram("work cpu    ", r.cpu)
     << FormatTimingHistogram("wake latency", r.wake_latency) << FormatTimingHistogram("period      ", r.period);
  os << "  safety: non-finite " << r.safety.non_finite << ", force clamped " << r.safety.force_clamped
     << ", torque clamped " << r.safety.torque_clamped << ", device silent " << r.safety.device_silent
     << ", loop stalls " << r.safety.loop_stalls << ", faults " << r.safety.faults << "\n";
  os << "  coherence resets (haptic body faster than max_point_speed): " << r.coherence_resets << "\n";
  os << "  contact faults (queries the model refused, e.g. a deformation of the wrong size): " << r.contact_faults
     << "\n";
  if (r.device_input.received > 0 || r.device_input.rejected() > 0)
    os << "  device input: " << FormatDeviceInputStats(r.device_input) << "\n";
  if (!r.largest_misses.empty()) os << FormatLargestMisses(r.largest_misses, r.period_ns);
  return os.str();
}

}  // namespace contactlab
