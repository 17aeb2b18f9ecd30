// SO(3) helpers for the virtual-coupling solve (Barbič & James 2008, sec. 5).
#include "geometry/rotation_math.h"

#include <cmath>

namespace contactlab {

Eigen::Vector3d CalcRotationVector(const Eigen::Quaterniond& q_in) {
  // Use the shortest rotation (w >= 0), then angle = 2 atan2(|v|, w).
  Eigen::Quaterniond q = q_in;
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v / q.w();  // small-angle limit, exact to O(|v|^3)
  const double angle = 2.0 * std::atan2(s, q.w());
  return (angle / s) * v;
}

Eigen::Matrix3d CalcInverseRightJacobian(const Eigen::Vector3d& phi) {
  const double t = phi.norm();
  const Eigen::Matrix3d S = Skew(phi);
  // J_r^{-1} = I + S/2 + c(t) S^2, c = 1/t^2 - (1 + cos t) / (2 t sin t); c -> 1/12 as t -> 0.
  double c;
  if (t < 1e-4) {
    c = 1.0 / 12.0 + t * t / 720.0;
  } else {
    c = 1.0 / (t * t) - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  }
  return Eigen::Matrix3d::Identity() + 0.5 * S + c * S * S;
}

}  // namespace contactlab
