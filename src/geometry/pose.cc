#include "geometry/pose.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {

Pose Interpolate(const Pose& a, const Pose& b, double s) {
  return {a.rotation.slerp(s, b.rotation).normalized(), (1.0 - s) * a.translation + s * b.translation};
}

Eigen::Quaterniond RotationFromVector(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-300) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

Pose ParsePose(const std::string& text, const std::string& where) {
  const std::vector<double> v = ParseNumberList(text, where + ": pose component");
  if (v.size() != 7) Fail(where, "a pose needs 7 numbers x,y,z,qw,qx,qy,qz; got " + std::to_string(v.size()));
  const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (const std::optional<std::string> e = NonUnitQuaternionError(q)) Fail(where, *e);
  return {UnitQuaternion(q), Eigen::Vector3d(v[0], v[1], v[2])};
}

std::optional<std::string> NonUnitQuaternionError(const Eigen::Quaterniond& q) {
  // The length through UnitQuaternion's scaling, so that a huge quaternion does not overflow.
  const double m = q.coeffs().cwiseAbs().maxCoeff();
  const double length = m > 0 ? m * (q.coeffs() / m).norm() : 0.0;
  if (std::abs(length - 1) <= kUnitQuaternionTolerance) return std::nullopt;
  if (length == 0) return std::string("the quaternion is zero; a pose is x, y, z, qw, qx, qy, qz with a unit quaternion");
  char text[256];
  std::snprintf(text, sizeof text,
                "the quaternion (qw, qx, qy, qz) = (%.9g, %.9g, %.9g, %.9g) has length %.9g, not 1 (within %g); a "
                "pose is x, y, z, qw, qx, qy, qz with a unit quaternion",
                q.w(), q.x(), q.y(), q.z(), length, kUnitQuaternionTolerance);
  return std::string(text);
}

Eigen::Quaterniond UnitQuaternion(const Eigen::Quaterniond& q) {
  const double m = q.coeffs().cwiseAbs().maxCoeff();
  if (!(m > 0)) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(q.coeffs() / m).normalized();
}

}  // namespace contactlab
