#include "experiment/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace contactlab {
namespace {

TEST(Metrics, AStepHasOneJumpOfKnownSize) {
  std::vector<Eigen::Vector3d> f(500, Eigen::Vector3d(0.1, -0.2, 1.0));
  for (int k = 250; k < 500; ++k) f[k] += Eigen::Vector3d(0, 1.5, -2.0);  // |jump| = 2.5
  std::vector<Pose> poses(500);
  for (int k = 0; k < 500; ++k) poses[k].translation.x() = 1e-5 * k;
  const ContinuityMetrics m = ForceContinuity(f, poses, 1e-3, 0.05, 100);
  EXPECT_NEAR(m.max_jump, 2.5, 1e-12);
  EXPECT_EQ(m.max_jump_cycle, 250);
  EXPECT_NEAR(m.lipschitz, 2.5 / 1e-5, 1e-3);
}

TEST(Metrics, ASineHasItsEnergyAtItsFrequency) {
  const double dt = 1e-3, f0 = 37.0;
  std::vector<double> s(4096);
  for (std::size_t k = 0; k < s.size(); ++k) s[k] = 3.0 + 2.0 * std::sin(2 * M_PI * f0 * k * dt);
  EXPECT_NEAR(DominantFrequency(s, dt), f0, 1000.0 / 4096);
  EXPECT_LT(HighFrequencyShare(s, dt, 60), 0.02);
  EXPECT_GT(HighFrequencyShare(s, dt, 20), 0.98);
}

TEST(Metrics, LinearForceOfPositionHasItsSlopeAsLipschitzConstant) {
  std::vector<Eigen::Vector3d> f;
  std::vector<Pose> poses;
  for (int k = 0; k < 200; ++k) {
    Pose p;
    p.translation = Eigen::Vector3d(1e-4 * k * k / 200.0, 0, 0);  // uneven steps
    poses.push_back(p);
    f.push_back(Eigen::Vector3d(-750.0 * p.translation.x(), 0, 0));
  }
  EXPECT_NEAR(ForceContinuity(f, poses, 1e-3, 0.05, 100).lipschitz, 750.0, 1e-6);
}

TEST(Metrics, FittedOrderRecoversAPowerLaw) {
  std::vector<double> n = {1000, 4000, 16000, 64000}, e;
  for (double x : n) e.push_back(3.0 * std::pow(x, -0.75));
  EXPECT_NEAR(FittedOrder(n, e), 0.75, 1e-12);
  EXPECT_TRUE(std::isnan(FittedOrder({1000}, {0.1})));
}

TEST(Metrics, TimingQuantilesAndLevelSwitches) {
  std::vector<double> us;
  for (int k = 1; k <= 100; ++k) us.push_back(k);
  std::vector<int> level(1000, 3);
  for (int k = 500; k < 1000; ++k) level[k] = 4;
  level[700] = 3;  // 3 switches over one second
  const TimingMetrics t = Timing(us, level, 1e-3);
  EXPECT_EQ(t.median_us, 50);
  EXPECT_EQ(t.p99_us, 99);
  EXPECT_EQ(t.max_us, 100);
  EXPECT_NEAR(t.level_switches_per_second, 3.0, 1e-12);
}

TEST(Metrics, DirectionAndMagnitudeErrorsAgainstAReference) {
  std::vector<Eigen::Vector3d> f, ref;
  for (int k = 0; k < 10; ++k) {
    ref.emplace_back(0, 0, 1.0 + k);
    f.push_back(Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitX()) * ref.back() * 1.1);
  }
  const ErrorMetrics e = ErrorAgainstReference(f, ref, std::vector<bool>(10, true));
  EXPECT_NEAR(e.max_direction_deg, 10.0, 1e-9);
  const double expected = std::sqrt(1.1 * 1.1 + 1 - 2 * 1.1 * std::cos(10 * M_PI / 180));
  EXPECT_NEAR(e.rms_relative, expected, 1e-12);
  EXPECT_EQ(e.samples, 10);
}

}  // namespace
}  // namespace contactlab
