#include "geometry/pose.h"

#include <gtest/gtest.h>

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
  const Pose p = ParsePose("1,2,3,2,0,0,0", "--pose-b");
  EXPECT_NEAR(p.rotation.w(), 1.0, 1e-15);
}

}  // namespace
}  // namespace contactlab
