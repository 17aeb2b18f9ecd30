// Tests of deadline misses with a cause (haptics/deadline_miss.h): the top-ten keeper against a
// brute-force sort, and the overrun / preempted rule on hand-made records and in the loop under
// simulated time, at 1 kHz and at the other rates a scene's cycle sets.
#include "haptics/deadline_miss.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
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

// Offers COUNT misses whose wall times are drawn from [0, RANGE) (a small range: many ties)
// and checks the keeper against a stable sort of all of them, largest first: the same cycles
// in the same order (among equal wall times the earlier is kept and listed first).
void CheckKeeperAgainstSort(int count, std::int64_t range, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::int64_t> wall(0, range - 1);
  LargestMisses keeper;
  std::vector<MissRecord> all;
  for (int i = 0; i < count; ++i) {
    MissRecord m;
    m.cycle = i;
    m.wall_ns = wall(rng);
    keeper.Offer(m);
    all.push_back(m);
  }
  std::stable_sort(all.begin(), all.end(), [](const MissRecord& a, const MissRecord& b) { return a.wall_ns > b.wall_ns; });
  const int expected = std::min(count, LargestMisses::kCapacity);
  ASSERT_EQ(keeper.size(), expected) << "count " << count << ", seed " << seed;
  for (int i = 0; i < expected; ++i) {
    EXPECT_EQ(keeper[i].wall_ns, all[i].wall_ns) << "rank " << i << ", count " << count << ", seed " << seed;
    EXPECT_EQ(keeper[i].cycle, all[i].cycle) << "rank " << i << ", count " << count << ", seed " << seed;
  }
}

TEST(LargestMisses, KeepsExactlyTheTenLargestAsASortWould) {
  for (int count : {0, 1, 9, 10, 11, 37, 1000, 20000})
    for (std::uint32_t seed : {1u, 2u, 3u}) {
      CheckKeeperAgainstSort(count, 1'000'000'000, seed);  // nearly all distinct
      CheckKeeperAgainstSort(count, 7, seed);              // mostly ties
    }
}

TEST(LargestMisses, AscendingAndDescendingInputsKeepTheTopTen) {
  LargestMisses up, down;
  for (int i = 0; i < 100; ++i) {
    up.Offer(MissRecord{.cycle = i, .wall_ns = i});
    down.Offer(MissRecord{.cycle = 99 - i, .wall_ns = 99 - i});
  }
  ASSERT_EQ(up.size(), 10);
  ASSERT_EQ(down.size(), 10);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(up[i].cycle, 99 - i);
    EXPECT_EQ(down[i].cycle, 99 - i);
  }
}

// The rule: overrun when the work's thread CPU time exceeds the period, whatever the wall time.
TEST(ClassifyMiss, OverrunOnlyWhenTheWorkAloneExceedsThePeriod) {
  constexpr std::int64_t period = 1 * kMs;
  EXPECT_EQ(ClassifyMiss(period + 1, period), MissCause::kOverrun);
  EXPECT_EQ(ClassifyMiss(3 * kMs, period), MissCause::kOverrun);
  EXPECT_EQ(ClassifyMiss(period, period), MissCause::kPreempted);  // would just have made it
  EXPECT_EQ(ClassifyMiss(0, period), MissCause::kPreempted);       // a wake-up stall
  EXPECT_EQ(ClassifyMiss(999'999, period), MissCause::kPreempted);
  EXPECT_EQ(ClassifyMiss(250'001, 250'000), MissCause::kOverrun);   // 4 kHz
  EXPECT_STREQ(MissCauseName(MissCause::kOverrun), "overrun");
  EXPECT_STREQ(MissCauseName(MissCause::kPreempted), "preempted");
}

// A contact model that, on chosen cycles, computes (Work: wall and CPU time) or loses its core
// (Advance: wall time only) for simulated time.
class TimedModel final : public ContactModel {
 public:
  TimedModel(ContactModel& inner, testing::SimulatedLoopClock& clock) : inner_(inner), clock_(clock) {}
  std::string_view name() const override { return "timed"; }
  ContactResult Evaluate(const ContactQuery& q) override {
    for (const Event& e : events)
      if (e.cycle == q.cycle) {
        if (e.work_ns > 0) clock_.Work(e.work_ns);
        if (e.lost_ns > 0) clock_.Advance(e.lost_ns);
      }
    return inner_.Evaluate(q);
  }
  void Reset() override { inner_.Reset(); }

  struct Event {
    std::int64_t cycle;
    std::int64_t work_ns;  // computing
    std::int64_t lost_ns;  // not running
  };
  std::vector<Event> events;

 private:
  ContactModel& inner_;
  testing::SimulatedLoopClock& clock_;
};

// In simulated time: a cycle that computes for 3 ms overran; one that lost its core for 5 ms,
// and one that computed 0.6 ms and lost 0.6 ms, were preempted; one that computed 0.9 ms made
// its deadline. The report counts and lists them, largest first, with their times and work.
TEST(HapticLoop, MissesAreSplitIntoOverrunAndPreemptedByTheCyclesCpuTime) {
  HalfspaceContactModel inner(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  testing::SimulatedLoopClock clock;
  TimedModel model(inner, clock);
  model.events = {{100, 3 * kMs, 0}, {200, 0, 5 * kMs}, {300, 600'000, 600'000}, {400, 900'000, 0}};
  SimDevice device(SimDeviceParams{}, [](double) { return Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.005)); });
  HapticCycle cycle(device, &model, HapticCycleConfig{});
  HapticLoopOptions opt;
  opt.try_realtime = false;
  opt.duration_seconds = 0.5;
  opt.watchdog_seconds = 0;  // no watchdog: nothing here is about it
  HapticLoop loop(cycle, opt, clock);
  const HapticLoopReport report = loop.Run();
  std::printf("%s", FormatLoopReport(report).c_str());

  EXPECT_EQ(report.deadline_misses, 3);
  EXPECT_EQ(report.misses_overrun, 1);
  EXPECT_EQ(report.misses_preempted, 2);
  EXPECT_EQ(report.period_ns, kMs);
  ASSERT_EQ(report.largest_misses.size(), 3);
  const MissRecord& first = report.largest_misses[0];
  EXPECT_EQ(first.cycle, 200);
  EXPECT_EQ(first.wall_ns, 5 * kMs);
  EXPECT_EQ(first.wake_ns, 0);
  EXPECT_EQ(first.work_ns, 5 * kMs);
  EXPECT_EQ(first.cpu_ns, 0);
  EXPECT_EQ(first.cause, MissCause::kPreempted);
  EXPECT_GT(first.points_in_contact, 0);  // what the cycle did travels with it
  EXPECT_GT(first.nodes_visited, 0);
  const MissRecord& second = report.largest_misses[1];
  EXPECT_EQ(second.cycle, 100);
  EXPECT_EQ(second.cpu_ns, 3 * kMs);
  EXPECT_EQ(second.cause, MissCause::kOverrun);
  const MissRecord& third = report.largest_misses[2];
  EXPECT_EQ(third.cycle, 300);
  EXPECT_EQ(third.wall_ns, 1'200'000);
  EXPECT_EQ(third.cpu_ns, 600'000);
  EXPECT_EQ(third.cause, MissCause::kPreempted);
  // The CPU time is in the histogram beside the wall time: 3 ms is its largest sample.
  EXPECT_EQ(report.cpu.count(), report.work.count());
  EXPECT_DOUBLE_EQ(report.cpu.max_seconds(), 3e-3);
  EXPECT_NE(FormatLoopReport(report).find("deadline misses 3 (overrun 1, preempted 2)"), std::string::npos);
}

// A scene's cycle is the loop's rate: 1 / cycle_seconds, refused outside [10 Hz, 100 kHz] with
// the place named; the spin before each release is 50 us, at most half the period.
TEST(HapticLoop, TheRateIsTheInverseOfTheCycleAndTheSpinFitsInThePeriod) {
  EXPECT_DOUBLE_EQ(LoopRateOfCycle(1e-3, "scene"), 1000.0);
  EXPECT_DOUBLE_EQ(LoopRateOfCycle(1e-4, "scene"), 10000.0);
  EXPECT_DOUBLE_EQ(LoopRateOfCycle(2e-3, "scene"), 500.0);
  EXPECT_EQ(LoopPeriodNs(1000), kMs);
  EXPECT_EQ(LoopPeriodNs(10000), 100'000);
  EXPECT_EQ(LoopPeriodNs(3000), 333'333);  // to the nearest nanosecond
  EXPECT_DOUBLE_EQ(LoopRateOfCycle(0.1, "scene"), 10.0);
  for (const double bad : {1e-6, 0.0, -1e-3, std::nan(""), HUGE_VAL, 0.1001, 10.0, 1e5, 1e300}) {
    try {
      (void)LoopRateOfCycle(bad, "s.yaml: model.cycle_seconds");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("s.yaml: model.cycle_seconds"), std::string::npos) << e.what();
    }
  }
  for (const double hz : {10.0, 500.0, 1000.0, 10000.0, 20000.0, 100000.0}) {
    const double spin = LoopSpinSeconds(hz);
    EXPECT_LE(spin, 50e-6) << hz;
    EXPECT_LE(spin, 0.5 / hz) << hz;
    EXPECT_GT(spin, 0.0) << hz;
  }
  EXPECT_DOUBLE_EQ(LoopSpinSeconds(1000), 50e-6);
  EXPECT_DOUBLE_EQ(LoopSpinSeconds(20000), 25e-6);
}

// model.cycle_seconds: 10 once made `session --duration 1` wait 10 s for its first release
// and end with no cycle: the loop's wait never runs past the end time. At 10 Hz (the slowest
// rate) a 50 ms run ends at 50 ms, with no cycle, instead of at the 100 ms release.
// A box pressed into a halfspace at the slowest rate, 10 Hz, for DURATION_SECONDS of simulated time.
struct SlowLoop {
  explicit SlowLoop(double duration_seconds) {
    config.cycle_seconds = 1.0 / kMinLoopRateHz;
    opt.rate_hz = kMinLoopRateHz;
    opt.spin_seconds = LoopSpinSeconds(opt.rate_hz);
    opt.try_realtime = false;
    opt.duration_seconds = duration_seconds;
    opt.watchdog_seconds = 0;
  }
  HalfspaceContactModel model{MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0};
  testing::SimulatedLoopClock clock;
  SimDevice device{SimDeviceParams{}, [](double) { return Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.005)); }};
  HapticCycleConfig config;
  HapticLoopOptions opt;
};

TEST(HapticLoop, TheWaitForASlowReleaseEndsAtTheEndTime) {
  SlowLoop s(0.05);
  HapticCycle cycle(s.device, &s.model, s.config);
  HapticLoop loop(cycle, s.opt, s.clock);
  const HapticLoopReport report = loop.Run();
  EXPECT_EQ(report.cycles, 0);
  EXPECT_EQ(report.run_ns, 50 * kMs);
}

// SIGINT was honoured 8 s late and SIGTERM not at all while the loop waited for a far release
// (the wait looped on EINTR without looking at the stop): the loop now waits in slices of
// kLoopWaitSliceNs and looks at its stop flag after each. Paused inside the first slice of a
// 10 Hz loop's wait, a stop ends the loop at that slice's end, before the release and its cycle.
TEST(HapticLoop, AStopDuringASlowWaitEndsTheLoopWithinASlice) {
  SlowLoop s(10);
  const std::int64_t start = s.clock.NowNs();
  HapticCycle cycle(s.device, &s.model, s.config);
  HapticLoop loop(cycle, s.opt, s.clock);
  s.clock.PauseAt(start + 1);  // the first wait's first slice
  loop.Start();
  ASSERT_TRUE(s.clock.WaitUntilPaused());
  loop.RequestStop();
  s.clock.Resume();
  const HapticLoopReport report = loop.Join();
  EXPECT_EQ(report.cycles, 0);
  EXPECT_EQ(report.run_ns, kLoopWaitSliceNs);
  EXPECT_EQ(s.device.held_wrench().force, Eigen::Vector3d::Zero());
}

// At 10 kHz in simulated time the loop runs a cycle every 100 us: 0.2 s is 2,000 cycles with
// every period 100 us, and a cycle that computes for 150 us (inside a 1 kHz budget) is an
// overrun here, one that computes 90 us is not a miss. The report states the rate and the loop
// thread's CPU time: the simulated work, and nothing else (the simulated wait costs none).
TEST(HapticLoop, AtTenKilohertzTheDeadlineIsTheTenthOfAMillisecond) {
  HalfspaceContactModel inner(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), 3), 1000.0);
  testing::SimulatedLoopClock clock;
  TimedModel model(inner, clock);
  model.events = {{500, 150'000, 0}, {900, 90'000, 0}};
  SimDevice device(SimDeviceParams{}, [](double) { return Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.005)); });
  HapticCycle cycle(device, &model, HapticCycleConfig{.cycle_seconds = 1e-4});
  HapticLoopOptions opt;
  opt.rate_hz = 10000;
  opt.spin_seconds = LoopSpinSeconds(opt.rate_hz);
  opt.try_realtime = false;
  opt.duration_seconds = 0.2;
  opt.watchdog_seconds = 0;
  HapticLoop loop(cycle, opt, clock);
  const HapticLoopReport report = loop.Run();
  const std::string text = FormatLoopReport(report);
  std::printf("%s", text.c_str());

  EXPECT_EQ(report.period_ns, 100'000);
  EXPECT_DOUBLE_EQ(report.rate_hz, 10000.0);
  EXPECT_EQ(report.spin_ns, 50'000);
  // Releases at 100 us, 200 us, ... up to (not at) 0.2 s, one skipped after the overrun.
  EXPECT_EQ(report.cycles + report.skipped_cycles, 1999);
  EXPECT_EQ(report.deadline_misses, 1);
  EXPECT_EQ(report.misses_overrun, 1);
  ASSERT_EQ(report.largest_misses.size(), 1);
  EXPECT_EQ(report.largest_misses[0].cycle, 500);
  EXPECT_EQ(report.loop_cpu_ns, 240'000);
  EXPECT_EQ(report.work_cpu_ns, 240'000);
  EXPECT_EQ(report.run_ns, 200'000'000);
  EXPECT_NEAR(report.period.QuantileSeconds(0.5).value_or(0) * 1e6, 100.0, 1.0);
  EXPECT_NE(text.find("rate 10000 Hz (period 100 us, spin 50 us before each release)"), std::string::npos) << text;
  EXPECT_NE(text.find("work 0.1 %"), std::string::npos) << text;
}

}  // namespace
}  // namespace contactlab
