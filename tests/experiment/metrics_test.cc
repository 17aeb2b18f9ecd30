#include "experiment/studies/contact/convergence_table.h"
#include "experiment/studies/contact/metrics.h"
#include "experiment/studies/contact/result_csv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

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

// A model whose law is 2.5x too soft and 10° off: the fit recovers 2.5 whatever the
// magnitudes, the calibrated error is what the angle alone leaves, 2 sin(5°).
TEST(Metrics, CalibrationRecoversAKnownStiffnessScale) {
  std::vector<Eigen::Vector3d> f, ref;
  std::vector<bool> has(12, true);
  for (int k = 0; k < 12; ++k) {
    ref.emplace_back(0.3 * k, 0, 1.0 + 0.7 * k * k);  // in the plane the rotation keeps
    f.push_back(Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitY()) * ref.back() / 2.5);
  }
  has[3] = false;
  f[3] = Eigen::Vector3d(1e6, 0, 0);  // no reference at cycle 3: ignored
  const ErrorMetrics e = ErrorAgainstReference(f, ref, has);
  EXPECT_NEAR(e.scale, 2.5, 1e-12);
  EXPECT_NEAR(e.rms_relative_calibrated, 2 * std::sin(5 * M_PI / 180), 1e-12);
  EXPECT_GT(e.rms_relative, 0.6);  // raw: mostly the 2.5x
  EXPECT_NEAR(e.median_direction_deg, 10, 1e-9);
  EXPECT_NEAR(e.p95_direction_deg, 10, 1e-9);
  EXPECT_EQ(e.samples, 11);
}

// Direction quantiles: angles 0..19° over 20 cycles: median (nearest rank) 9°, p95 18°, max 19°;
// a model with no force at all has no scale.
TEST(Metrics, DirectionQuantilesAndAModelWithoutForce) {
  std::vector<Eigen::Vector3d> f, ref, zero;
  for (int k = 0; k < 20; ++k) {
    ref.emplace_back(0, 0, 1);
    f.push_back(Eigen::AngleAxisd(k * M_PI / 180, Eigen::Vector3d::UnitX()) * ref.back());
    zero.emplace_back(0, 0, 0);
  }
  const ErrorMetrics e = ErrorAgainstReference(f, ref, std::vector<bool>(20, true));
  EXPECT_NEAR(e.median_direction_deg, 9, 1e-9);
  EXPECT_NEAR(e.p95_direction_deg, 18, 1e-9);
  EXPECT_NEAR(e.max_direction_deg, 19, 1e-9);
  const ErrorMetrics none = ErrorAgainstReference(zero, ref, std::vector<bool>(20, true));
  EXPECT_TRUE(std::isnan(none.scale));
  EXPECT_NEAR(none.rms_relative, 1, 1e-12);
  EXPECT_NEAR(none.median_direction_deg, 180, 1e-9);
}

// Continuity relative to the force scale: 5 cycles apart, 10 at 2 N, 5 at 5 N; the median
// force in contact is 2 N and the largest jump 3 N, so the relative jump is 1.5, and a model
// with ten times the stiffness has the same.
TEST(Metrics, RelativeJumpOfAKnownStep) {
  std::vector<Eigen::Vector3d> f;
  std::vector<Pose> poses;
  for (int k = 0; k < 20; ++k) {
    f.emplace_back(0, 0, k < 5 ? 0.0 : k < 15 ? 2.0 : 5.0);
    poses.push_back(Pose::FromTranslation(Eigen::Vector3d(1e-4 * k, 0, 0)));
  }
  const double scale = MedianForceInContact(f);
  EXPECT_DOUBLE_EQ(scale, 2.0);
  const ContinuityMetrics m = ForceContinuity(f, poses, 1e-3, 0.05, 100);
  EXPECT_NEAR(m.max_jump / scale, 1.5, 1e-12);
  for (auto& v : f) v *= 10;
  EXPECT_NEAR(ForceContinuity(f, poses, 1e-3, 0.05, 100).max_jump / MedianForceInContact(f), 1.5, 1e-12);
  EXPECT_EQ(MedianForceInContact(std::vector<Eigen::Vector3d>(4, Eigen::Vector3d::Zero())), 0.0);
}

// The order's 95 % interval: zero for an exact power law; for log-errors with residuals
// +e, -e, +e, -e around a slope the standard error is e sqrt(4 / 2 / sxx) (here
// sxx = 5 ln(4)^2 over x = 0, ln 4, 2 ln 4, 3 ln 4 ... as computed), times t(0.975, 2) = 4.303.
TEST(Metrics, FittedOrderIntervalFromTheResiduals) {
  const std::vector<double> n = {256, 1024, 4096, 16384};
  std::vector<double> exact, noisy;
  const double e = 0.1;
  for (std::size_t i = 0; i < n.size(); ++i) {
    exact.push_back(3.0 * std::pow(n[i], -0.75));
    noisy.push_back(exact.back() * std::exp(i % 2 == 0 ? e : -e));
  }
  EXPECT_NEAR(FittedOrderHalfWidth95(n, exact), 0, 1e-12);
  EXPECT_NEAR(FittedOrder(n, exact), 0.75, 1e-12);
  // x_i = ln 256 + i ln 4: sxx = ln(4)^2 (2.25 + 0.25 + 0.25 + 2.25) = 5 ln(4)^2. The residuals
  // of +-e about the fitted line: the alternating pattern's projection on x - mean is
  // -e (3 ln 4 ... ) / sxx; computed from the definition below rather than by hand.
  const double l4 = std::log(4.0), sxx = 5 * l4 * l4;
  const double xc[] = {-1.5 * l4, -0.5 * l4, 0.5 * l4, 1.5 * l4};
  const double r0[] = {e, -e, e, -e};
  double b = 0;
  for (int i = 0; i < 4; ++i) b += xc[i] * r0[i] / sxx;
  double rss = 0;
  for (int i = 0; i < 4; ++i) {
    const double mean = 0;  // the alternating residuals have mean zero
    rss += std::pow(r0[i] - mean - b * xc[i], 2);
  }
  EXPECT_NEAR(FittedOrderHalfWidth95(n, noisy), 4.303 * std::sqrt(rss / 2 / sxx), 1e-9);
  EXPECT_TRUE(std::isnan(FittedOrderHalfWidth95({256, 1024}, {0.1, 0.05})));
}

// convergence.csv: two seeds of each size pool into one RMS per size; the seed axis and the
// points axis (sweep.points, named like summary.csv's own points column) are not groups; the errors 0.4 / 0.3 at 256 and 0.1 / 0.0 (RMS 0.5 / sqrt(2) and 0.1 / sqrt(2))
// at 4096 fall as 4096^-0.5 / 256^-0.5 = 1/4 to 1/5 — fitted order log(5)/log(16).
TEST(ConvergenceTable, PoolsSeedsAsRmsAndFitsTheOrder) {
  const std::string summary =
      "experiment,job,method,scene.bodies[role=pointshell].pointshell.seed,sweep.points,model,points,rms_rel_error\n"
      "e,0,random,1,256,m,256,0.4\n"
      "e,1,random,2,256,m,256,0.3\n"
      "e,2,random,1,4096,m,4096,0.1\n"
      "e,3,random,2,4096,m,4096,0\n"
      "e,4,voxel,1,256,m,256,\n"
      "e,4,voxel,1,256,fcl,,0.2\n";
  const std::string table = ConvergenceCsv(summary);
  std::istringstream in(table);
  std::string header, row, extra;
  std::getline(in, header);
  std::getline(in, row);
  // voxel had no reference (an empty error) and fcl reads no pointshell (empty points): no group.
  EXPECT_FALSE(std::getline(in, extra)) << table;
  EXPECT_EQ(header, "group,samples,fitted_order,order_ci95,points,errors");
  const std::vector<std::string> cells = SplitCsvLine(row);
  ASSERT_EQ(cells.size(), 6u) << table;
  EXPECT_EQ(cells[0], "m;method=random");
  EXPECT_EQ(cells[1], "2");
  EXPECT_NEAR(std::stod(cells[2]), std::log(5.0) / std::log(16.0), 1e-3);
  EXPECT_EQ(cells[3], "nan");  // two sizes: no interval
  EXPECT_EQ(cells[4], "256 4096");
  EXPECT_EQ(cells[5], "0.3536 0.07071");
}

}  // namespace
}  // namespace contactlab
