// Tests of the safety filter before the device (docs/architecture.md "Errors and safety"):
// clamps, ramp, non-finite replacement, device-silence and loop-stall watchdogs.
#include "haptics/safety_filter.h"

#include <gtest/gtest.h>

#include <limits>

#include "util/error.h"

namespace contactlab {
namespace {

constexpr std::int64_t kMs = 1000000;

SafetyParams Params() {
  SafetyParams p;
  p.max_force = 4.0;
  p.max_torque = 0.3;
  p.ramp_seconds = 1.0;
  p.device_timeout_seconds = 0.05;
  p.loop_stall_seconds = 0.01;
  return p;
}

Wrench MakeWrench(double fx, double tz) {
  Wrench w;
  w.force = Eigen::Vector3d(fx, 0, 0);
  w.torque = Eigen::Vector3d(0, 0, tz);
  return w;
}

// Runs the filter from t=0 at 1 kHz with a fresh sample every cycle up to cycle N, returning
// the last output.
Wrench RunSteady(SafetyFilter& f, const Wrench& in, int n, std::int64_t* t) {
  Wrench out;
  for (int i = 0; i < n; ++i) {
    *t += kMs;
    out = f.Filter(in, *t, *t);
  }
  return out;
}

TEST(SafetyFilter, ClampsForceAndTorqueToDeviceLimitsKeepingDirection) {
  SafetyFilter f(Params());
  f.Start(0);
  std::int64_t t = 0;
  Wrench in;
  in.force = Eigen::Vector3d(30, -40, 0);  // |F| = 50 N
  in.torque = Eigen::Vector3d(0, 1, 0);
  const Wrench out = RunSteady(f, in, 1500, &t);  // past the ramp
  EXPECT_NEAR(out.force.norm(), 4.0, 1e-12);
  EXPECT_NEAR(out.force.normalized().dot(in.force.normalized()), 1.0, 1e-12);
  EXPECT_NEAR(out.torque.norm(), 0.3, 1e-12);
  EXPECT_EQ(f.stats().force_clamped, 1500);
  EXPECT_EQ(f.stats().torque_clamped, 1500);
  // Within limits: passes unchanged.
  const Wrench small = MakeWrench(1.0, 0.1);
  const Wrench out2 = RunSteady(f, small, 1, &t);
  EXPECT_EQ(out2.force, small.force);
  EXPECT_EQ(out2.torque, small.torque);
}

TEST(SafetyFilter, RampIsLinearAndReachesFullScaleAtOneSecond) {
  SafetyFilter f(Params());
  f.Start(0);
  const Wrench in = MakeWrench(2.0, 0.2);
  std::int64_t t = 0;
  for (int i = 1; i <= 1200; ++i) {
    t += kMs;
    const Wrench out = f.Filter(in, t, t);
    const double s = std::min(1.0, i / 1000.0);
    ASSERT_NEAR(out.force.x(), 2.0 * s, 1e-12) << "cycle " << i;
    ASSERT_NEAR(out.torque.z(), 0.2 * s, 1e-12);
  }
}

TEST(SafetyFilter, NonFiniteWrenchIsZeroedCountedAndRampRestarts) {
  SafetyFilter f(Params());
  f.Start(0);
  std::int64_t t = 0;
  RunSteady(f, MakeWrench(1, 0), 1500, &t);
  Wrench bad = MakeWrench(1, 0);
  bad.force.y() = std::numeric_limits<double>::quiet_NaN();
  t += kMs;
  const Wrench out = f.Filter(bad, t, t);
  EXPECT_EQ(out.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(out.torque, Eigen::Vector3d::Zero());
  bad.force.y() = std::numeric_limits<double>::infinity();
  t += kMs;
  f.Filter(bad, t, t);
  EXPECT_EQ(f.stats().non_finite, 2);
  EXPECT_EQ(f.stats().faults, 1);  // one fault episode
  // After the fault, force ramps in again from zero.
  const Wrench after = RunSteady(f, MakeWrench(1, 0), 100, &t);
  EXPECT_NEAR(after.force.x(), 0.1, 1e-9);
}

TEST(SafetyFilter, DeviceSilenceLongerThanTimeoutZeroesOutput) {
  SafetyFilter f(Params());
  f.Start(0);
  std::int64_t t = 0;
  RunSteady(f, MakeWrench(1, 0), 1500, &t);
  const std::int64_t last_sample = t;
  int zeroed = 0, passed = 0;
  for (int i = 1; i <= 100; ++i) {  // device silent for 100 ms, loop keeps running
    t += kMs;
    const Wrench out = f.Filter(MakeWrench(1, 0), t, last_sample);
    (out.force.norm() == 0 ? zeroed : passed)++;
  }
  EXPECT_EQ(passed, 50);  // within the 50 ms timeout the last command is still rendered
  EXPECT_EQ(zeroed, 50);
  EXPECT_EQ(f.stats().device_silent, 50);
  // The device comes back: output ramps in.
  const Wrench back = RunSteady(f, MakeWrench(1, 0), 500, &t);
  EXPECT_NEAR(back.force.x(), 0.5, 1e-9);
}

TEST(SafetyFilter, LoopStallLongerThanLimitZeroesOutput) {
  SafetyFilter f(Params());
  f.Start(0);
  std::int64_t t = 0;
  RunSteady(f, MakeWrench(1, 0), 1500, &t);
  t += 5 * kMs;  // a 5 ms gap: below the 10 ms limit
  EXPECT_GT(f.Filter(MakeWrench(1, 0), t, t).force.norm(), 0);
  t += 20 * kMs;  // a 20 ms stall
  EXPECT_EQ(f.Filter(MakeWrench(1, 0), t, t).force.norm(), 0);
  EXPECT_EQ(f.stats().loop_stalls, 1);
}

TEST(SafetyFilter, InvalidParametersAreRejectedByName) {
  SafetyParams p = Params();
  p.max_force = -1;
  try {
    SafetyFilter f(p);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("max_force"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contactlab
