// Rigid poses. Frames follow Drake's monogram notation: X_WB is the pose of body B in world W,
// p_WQ a point Q in W. A pose maps coordinates in the body frame to the parent frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace contactlab {

struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit quaternion
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();          // metres

  static Pose Identity() { return {}; }
  static Pose FromTranslation(const Eigen::Vector3d& p) { return {Eigen::Quaterniond::Identity(), p}; }

  Eigen::Matrix3d R() const { return rotation.toRotationMatrix(); }
  Eigen::Vector3d operator*(const Eigen::Vector3d& p_B) const { return rotation * p_B + translation; }
  Pose operator*(const Pose& X_BC) const {
    return {(rotation * X_BC.rotation).normalized(), rotation * X_BC.translation + translation};
  }
  Pose Inverse() const {
    const Eigen::Quaterniond q = rotation.conjugate();
    return {q, -(q * translation)};
  }
  Eigen::Isometry3d ToIsometry() const {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = R();
    X.translation() = translation;
    return X;
  }
};

// Interpolates between poses: linear in translation, slerp in rotation, S in [0, 1].
Pose Interpolate(const Pose& a, const Pose& b, double s);

// Q scaled to unit length, by its largest component first so that a huge quaternion (1e308)
// does not overflow its norm; a zero quaternion gives the identity. Q must be finite.
Eigen::Quaterniond UnitQuaternion(const Eigen::Quaterniond& q);

// How far from 1 the length of a pose's quaternion may be: a quaternion written with nine
// significant digits (%.9g, as session logs and result tables write it) is within 1e-8.
constexpr double kUnitQuaternionTolerance = 1e-6;

// What is wrong with Q (qw, qx, qy, qz) as a pose's rotation, or nothing when it is a unit
// quaternion (| |Q| - 1 | <= kUnitQuaternionTolerance). The message gives Q and its length and
// names the order x, y, z, qw, qx, qy, qz, so that a pose whose quaternion is not unit length
// (a typo, a swapped order, too few digits) is refused wherever a pose enters instead of
// being normalised silently. Q must be finite.
std::optional<std::string> NonUnitQuaternionError(const Eigen::Quaterniond& q);

// Rotation by the rotation vector W (axis times angle, radians).
Eigen::Quaterniond RotationFromVector(const Eigen::Vector3d& w);

// Parses "x,y,z,qw,qx,qy,qz" (a unit quaternion, NonUnitQuaternionError; normalised to
// double precision); throws Error naming WHERE.
Pose ParsePose(const std::string& text, const std::string& where);

}  // namespace contactlab
