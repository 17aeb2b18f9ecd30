#include "geometry/pose.h"

#include <cmath>
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
  Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (q.norm() < 1e-12) Fail(where, "pose quaternion is zero");
  return {UnitQuaternion(q), Eigen::Vector3d(v[0], v[1], v[2])};
}

Eigen::Quaterniond UnitQuaternion(const Eigen::Quaterniond& q) {
  const double m = q.coeffs().cwiseAbs().maxCoeff();
  if (!(m > 0)) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(q.coeffs() / m).normalized();
}

}  // namespace contactlab
