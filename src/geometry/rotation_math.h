// SO(3) helpers: rotation vectors and the inverse right Jacobian, for the virtual-coupling solve
// (Barbič & James 2008, sec. 5: "large rotation terms in the static equilibrium") and the
// proxy of continuous collision.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace contactlab {

// The rotation vector (axis times angle, radians, angle in [0, pi]) of the unit quaternion Q.
// Precondition: Q has unit norm. Allocation-free; never throws.
Eigen::Vector3d CalcRotationVector(const Eigen::Quaterniond& q);

// The inverse right Jacobian of SO(3) at rotation vector PHI: log(exp(PHI) exp(v)) =
// PHI + CalcInverseRightJacobian(PHI) v + O(|v|^2). Near |PHI| = pi the result grows without
// bound; callers keep |PHI| away from pi (the coupling saturates long before).
Eigen::Matrix3d CalcInverseRightJacobian(const Eigen::Vector3d& phi);

// The skew matrix [v]x with [v]x w = v x w.
inline Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

}  // namespace contactlab
