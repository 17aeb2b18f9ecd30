// Tests of the haptic loop's CPU pinning (haptics/cpu_affinity.h, `session --cpu N`): the
// affinity masks of the loop, its watchdog and threads started after a core was left, and
// --cpu values refused with the option named.
#include "haptics/cpu_affinity.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "haptics/halfspace_contact_model.h"
#include "haptics/haptic_cycle.h"
#include "haptics/haptic_loop.h"
#include "haptics/sim_device.h"
#include "haptics/simulated_loop_clock.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr std::int64_t kMs = 1000000;

// The CPUs in SET, ascending.
std::vector<int> CpusIn(const cpu_set_t& set) {
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  return cpus;
}

// The calling thread's mask, without allocating (for the haptic and watchdog threads).
cpu_set_t MaskOfThisThread() {
  cpu_set_t set;
  CPU_ZERO(&set);
  pthread_getaffinity_np(pthread_self(), sizeof(set), &set);
  return set;
}

// A thread that leaves a core, and every thread it starts afterwards, run on the other cores
// only: what a session's main thread does before it starts its logger, viewer and devices.
TEST(CpuAffinity, ThreadsStartedAfterLeavingACoreDoNotRunOnIt) {
  const std::vector<int> allowed = CpusOfThisThread();
  if (allowed.size() < 2) GTEST_SKIP() << "needs two CPUs; this process may use " << FormatCpuList(allowed);
  const int loop_cpu = allowed.back();
  int err = -1;
  std::vector<int> left, child;
  std::thread session([&] {
    err = KeepThisThreadOffCpu(loop_cpu);
    left = CpusOfThisThread();
    std::thread started([&] { child = CpusOfThisThread(); });
    started.join();
  });
  session.join();
  ASSERT_EQ(err, 0);
  std::vector<int> expected = allowed;
  expected.pop_back();
  EXPECT_EQ(left, expected);
  EXPECT_EQ(child, expected);
  EXPECT_EQ(CpusOfThisThread(), allowed);  // the test's own thread is untouched
}

// A device that records the affinity mask of the thread of its first Read (the loop thread)
// and of its first emergency zero (the watchdog thread).
class MaskRecordingDevice final : public HapticDevice {
 public:
  explicit MaskRecordingDevice(HapticDevice& inner) : inner_(inner) {
    CPU_ZERO(&read_mask);
    CPU_ZERO(&zero_mask);
  }
  std::string_view name() const override { return inner_.name(); }
  DeviceCapabilities capabilities() const override { return inner_.capabilities(); }
  bool Read(std::int64_t now_ns, DeviceState* out) override {
    if (!read_seen) {
      read_mask = MaskOfThisThread();
      read_seen = true;
    }
    return inner_.Read(now_ns, out);
  }
  void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t flags) override { inner_.Write(wrench, now_ns, flags); }
  void EmergencyZero() noexcept override {
    if (!zero_seen.load()) {
      zero_mask = MaskOfThisThread();
      zero_seen.store(true);
    }
    inner_.EmergencyZero();
  }

  cpu_set_t read_mask, zero_mask;
  bool read_seen = false;
  std::atomic<bool> zero_seen{false};

 private:
  HapticDevice& inner_;
};

// With options.cpu = N the loop thread runs on N alone and its watchdog (which zeroes the
// device during a 40 ms stall of simulated time) off N.
TEST(CpuAffinity, PinnedLoopRunsAloneOnItsCoreAndItsWatchdogOffIt) {
  const std::vector<int> allowed = CpusOfThisThread();
  if (allowed.size() < 2) GTEST_SKIP() << "needs two CPUs; this process may use " << FormatCpuList(allowed);
  const int loop_cpu = allowed.back();
  HalfspaceContactModel inner(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  testing::SimulatedLoopClock clock;
  SimDevice sim(SimDeviceParams{}, [](double) { return Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.005)); });
  MaskRecordingDevice device(sim);
  testing::ZeroCountingDevice counting(device);
  // Cycle 100 loses its core for 40 ms of simulated time, until the watchdog zeroed the device.
  struct : ContactModel {
    std::string_view name() const override { return "stall"; }
    ContactResult Evaluate(const ContactQuery& q) override {
      ContactResult r = inner->Evaluate(q);
      if (q.cycle == 100) {
        clock->Advance(40 * kMs);
        seen = counting->WaitForZeroes(1);
      }
      return r;
    }
    void Reset() override { inner->Reset(); }
    ContactModel* inner = nullptr;
    testing::SimulatedLoopClock* clock = nullptr;
    testing::ZeroCountingDevice* counting = nullptr;
    bool seen = false;
  } stall;
  stall.inner = &inner;
  stall.clock = &clock;
  stall.counting = &counting;
  HapticCycle cycle(counting, &stall, HapticCycleConfig{});
  HapticLoopOptions opt;
  opt.try_realtime = false;
  opt.duration_seconds = 0.2;
  opt.watchdog_seconds = 0.01;
  opt.cpu = loop_cpu;
  HapticLoop loop(cycle, opt, clock);
  const HapticLoopReport report = loop.Run();
  EXPECT_EQ(report.pinned_cpu, loop_cpu);
  ASSERT_TRUE(device.read_seen);
  EXPECT_EQ(CpusIn(device.read_mask), std::vector<int>{loop_cpu});
  ASSERT_TRUE(stall.seen) << "the watchdog did not zero the device during the stall";
  ASSERT_TRUE(device.zero_seen.load());
  const std::vector<int> watchdog = CpusIn(device.zero_mask);
  EXPECT_FALSE(watchdog.empty());
  EXPECT_EQ(std::count(watchdog.begin(), watchdog.end(), loop_cpu), 0) << FormatCpuList(watchdog);
  EXPECT_NE(FormatLoopReport(report).find("pinned to CPU " + std::to_string(loop_cpu)), std::string::npos);
}

// The message of the Error that F throws ("" when it throws none).
template <class F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// --cpu values that are not a CPU of this machine, or one the process may not use, or the only
// one it may use, are refused with the option named; a good one is returned.
TEST(CpuAffinity, BadLoopCpuIsRefusedNamingTheOption) {
  const int count = ConfiguredCpuCount();
  for (const std::string& bad : std::vector<std::string>{"-1", "x", "1.5", "", std::to_string(count), "99999999999"}) {
    const std::string message = ErrorOf([&] { ParseLoopCpu(bad, "--cpu"); });
    EXPECT_EQ(message.rfind("--cpu: ", 0), 0u) << "'" << bad << "' gave: " << message;
  }
  EXPECT_NE(ErrorOf([&] { ParseLoopCpu(std::to_string(count), "--cpu"); }).find("does not exist"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseLoopCpu("-1", "--cpu"); }).find("does not exist"), std::string::npos);

  const std::vector<int> allowed = CpusOfThisThread();
  if (allowed.size() < 2) {
    // One CPU: it cannot be the loop's alone.
    EXPECT_NE(ErrorOf([&] { ParseLoopCpu(std::to_string(allowed.front()), "--cpu"); }).find("only CPU"),
              std::string::npos);
    return;
  }
  EXPECT_EQ(ParseLoopCpu(std::to_string(allowed.back()), "--cpu"), allowed.back());
  // In a thread confined to one CPU: another is not allowed, and that one is the only one.
  std::string not_allowed, only;
  std::thread confined([&] {
    if (PinThisThreadToCpu(allowed.front()) != 0) return;
    not_allowed = ErrorOf([&] { ParseLoopCpu(std::to_string(allowed.back()), "--cpu"); });
    only = ErrorOf([&] { ParseLoopCpu(std::to_string(allowed.front()), "--cpu"); });
  });
  confined.join();
  EXPECT_NE(not_allowed.find("--cpu: CPU " + std::to_string(allowed.back()) + " is not among the CPUs"),
            std::string::npos)
      << not_allowed;
  EXPECT_NE(only.find("is the only CPU"), std::string::npos) << only;
}

TEST(CpuAffinity, CpuListsAreWrittenAsRanges) {
  EXPECT_EQ(FormatCpuList({}), "none");
  EXPECT_EQ(FormatCpuList({0}), "0");
  EXPECT_EQ(FormatCpuList({0, 1, 2, 3, 6}), "0-3,6");
  EXPECT_EQ(FormatCpuList({1, 3, 4}), "1,3-4");
}

TEST(HapticLoop, CpuOptionOutsideTheMachineIsRefused) {
  HalfspaceContactModel model(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  SimDevice device(SimDeviceParams{}, [](double) { return Pose::Identity(); });
  HapticCycle cycle(device, &model, HapticCycleConfig{});
  for (int bad : {-2, ConfiguredCpuCount()}) {
    HapticLoopOptions opt;
    opt.cpu = bad;
    EXPECT_NE(ErrorOf([&] { HapticLoop loop(cycle, opt); }).find("cpu must be"), std::string::npos) << bad;
  }
}

// A NaN duration compared false with "<= 0 runs until stopped" and with the end time, so the
// loop ran forever; an infinite or huge one overflows the clock's nanoseconds. Both are refused
// when the loop is made, before any cycle.
TEST(HapticLoop, NanInfiniteOrHugeDurationIsRefusedInsteadOfRunningForever) {
  HalfspaceContactModel model(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  SimDevice device(SimDeviceParams{}, [](double) { return Pose::Identity(); });
  HapticCycle cycle(device, &model, HapticCycleConfig{});
  for (double bad : {std::nan(""), HUGE_VAL, 1e300, 1.5 * kMaxLoopSeconds}) {
    HapticLoopOptions opt;
    opt.duration_seconds = bad;
    EXPECT_NE(ErrorOf([&] { HapticLoop loop(cycle, opt); }).find("duration_seconds must be a finite number"),
              std::string::npos)
        << bad;
  }
  for (double good : {0.0, -1.0, 0.5, kMaxLoopSeconds}) {
    HapticLoopOptions opt;
    opt.duration_seconds = good;
    EXPECT_EQ(ErrorOf([&] { HapticLoop loop(cycle, opt); }), "") << good;
  }
}

}  // namespace
}  // namespace contactlab
