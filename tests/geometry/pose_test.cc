#include "geometry/pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

TEST(Pose, InverseComposesToIdentity) {
  const Pose X{RotationFromVector(Eigen::Vector3d(0.3, -1.0 / 3.0, 0.7)), Eigen::Vector3d(0.1, 2.0, -1.0 / 3.0)};
  const Eigen::Vector3d p(0.25, -0.5, 1.0 / 7.0);
  EXPECT_LT(((X * X.Inverse()) * p - p).norm(), 1e-14);
  EXPECT_LT((X.Inverse() * (X * p) - p).norm(), 1e-14);
}

TEST(Pose, InterpolationHitsEndpointsAndMidpointAngle) {
  const Pose a = Pose::Identity();
  const Pose b{RotationFromVector(Eigen::Vector3d(0, 0, 1.2)), Eigen::Vector3d(1, 0, 0)};
  const Pose m = Interpolate(a, b, 0.5);
  EXPECT_NEAR(m.translation.x(), 0.5, 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(m.rotation).angle(), 0.6, 1e-12);
  EXPECT_LT((Interpolate(a, b, 1.0).R() - b.R()).norm(), 1e-12);
}

TEST(Pose, ParseRejectsBadText) {
  EXPECT_THROW(ParsePose("1,2,3", "--pose-b"), Error);
  EXPECT_THROW(ParsePose("1,2,3,0,0,0,0", "--pose-b"), Error);
  EXPECT_THROW(ParsePose("1,2,x,1,0,0,0", "--pose-b"), Error);
}

std::string Text(const Pose& X, double scale) {
  char text[256];
  std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", X.translation.x(), X.translation.y(),
                X.translation.z(), scale * X.rotation.w(), scale * X.rotation.x(), scale * X.rotation.y(),
                scale * X.rotation.z());
  return text;
}

// A pose's quaternion must be unit length within 1e-6: one scaled by 2, or by 1 +- 2e-6 (a
// mistyped digit), is refused naming the option, the order x, y, z, qw, qx, qy, qz and the
// length; every rotation written with nine significant digits (as session logs and result
// tables write poses) is accepted and read back to that precision.
TEST(Pose, ParseRefusesAQuaternionNotOfUnitLength) {
  const Pose X{RotationFromVector(Eigen::Vector3d(0.3, -1.0 / 3.0, 0.7)), Eigen::Vector3d(0.1, 2.0, -1.0 / 3.0)};
  for (const double scale : {2.0, 0.5, 1 + 2e-6, 1 - 2e-6, 0.0}) {
    const std::string e = testing::ErrorOf([&] { ParsePose(Text(X, scale), "--pose-a"); });
    EXPECT_EQ(e.rfind("--pose-a: ", 0), 0u) << scale << ": " << e;
    EXPECT_NE(e.find("x, y, z, qw, qx, qy, qz"), std::string::npos) << scale << ": " << e;
    if (scale == 2.0) EXPECT_NE(e.find("has length 2,"), std::string::npos) << e;
    if (scale == 0.0) EXPECT_NE(e.find("quaternion is zero"), std::string::npos) << e;
  }
  EXPECT_FALSE(NonUnitQuaternionError(Eigen::Quaterniond(1 + 5e-7, 0, 0, 0)).has_value());
  EXPECT_TRUE(NonUnitQuaternionError(Eigen::Quaterniond(1e200, 1e200, 0, 0)).has_value());  // no overflow to inf
  EXPECT_TRUE(NonUnitQuaternionError(Eigen::Quaterniond(1e-200, 0, 0, 0)).has_value());
  // Rotations about many axes by many angles, written with %.9g.
  for (int i = 0; i < 200; ++i) {
    const double a = 0.37 * i, b = 1.3 * i + 0.2;
    const Eigen::Vector3d w = (0.05 + 0.0157 * i) * Eigen::Vector3d(std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b));
    const Pose Y{RotationFromVector(w), Eigen::Vector3d(0.1, -0.2, 1.0 / 3.0)};
    const Pose parsed = ParsePose(Text(Y, 1.0), "--pose-b");
    EXPECT_LT(parsed.rotation.angularDistance(Y.rotation), 1e-8) << i;
    EXPECT_NEAR(parsed.rotation.norm(), 1.0, 1e-15) << i;
  }
}

}  // namespace
}  // namespace contactlab
