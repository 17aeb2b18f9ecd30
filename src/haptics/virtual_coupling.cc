// Static virtual coupling with quasi-static damping (Barbič & James 2008, sec. 5).
#include "haptics/virtual_coupling.h"

#include <cmath>
#include <string>

#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {
namespace {

// The coupling's two error terms: translation u = p_WD - p_WH, rotation phi = log(R_WD R_WH^T).
struct CouplingError {
  Eigen::Vector3d u;
  Eigen::Vector3d phi;
};

CouplingError CalcError(const Pose& X_WD, const Pose& X_WH) {
  return {X_WD.translation - X_WH.translation, CalcRotationVector(X_WD.rotation * X_WH.rotation.conjugate())};
}

// Derivative of s(v) = min(1, m / (k |v|)) k v with respect to v: k I in the linear region,
// (m / |v|) (I - v̂ v̂^T) when saturated.
Eigen::Matrix3d SaturationJacobian(const Eigen::Vector3d& v, double k, double m) {
  const double n = v.norm();
  if (k * n <= m) return k * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d vh = v / n;
  return (m / n) * (Eigen::Matrix3d::Identity() - vh * vh.transpose());
}

Eigen::Vector3d Saturate(const Eigen::Vector3d& v, double k, double m) {
  const double n = v.norm();
  if (k * n <= m) return k * v;
  return (m / n) * v;
}

}  // namespace

void VirtualCouplingParams::Validate(const char* where) const {
  auto positive = [&](double v, const char* name) {
    if (!std::isfinite(v) || v <= 0) Fail(where, std::string(name) + " must be finite and > 0, got " + std::to_string(v));
  };
  positive(k_vc, "k_vc");
  positive(k_vc_rot, "k_vc_rot");
  positive(max_force, "max_force");
  positive(max_torque, "max_torque");
  positive(max_step_translation, "max_step_translation");
  positive(max_step_rotation, "max_step_rotation");
  if (!std::isfinite(alpha) || alpha < 0 || alpha >= 1) Fail(where, "alpha must lie in [0, 1), got " + std::to_string(alpha));
}

Wrench CalcCouplingWrench(const Pose& X_WD, const Pose& X_WH, const VirtualCouplingParams& p) {
  const CouplingError e = CalcError(X_WD, X_WH);
  Wrench w;
  w.force = Saturate(e.u, p.k_vc, p.max_force);
  w.torque = Saturate(e.phi, p.k_vc_rot, p.max_torque);
  return w;
}

Matrix6d CalcCouplingGradient(const Pose& X_WD, const Pose& X_WH, const VirtualCouplingParams& p) {
  const CouplingError e = CalcError(X_WD, X_WH);
  Matrix6d K = Matrix6d::Zero();
  // du/dx = -I; dphi/dθ = -J_r^{-1}(phi) (perturbation exp([dθ]) R_WH on the right of R_WD R_WH^T).
  K.topLeftCorner<3, 3>() = -SaturationJacobian(e.u, p.k_vc, p.max_force);
  K.bottomRightCorner<3, 3>() = -SaturationJacobian(e.phi, p.k_vc_rot, p.max_torque) * CalcInverseRightJacobian(e.phi);
  return K;
}

Matrix6d CalcCouplingSolveGradient(const Pose& X_WD, const Pose& X_WH, const VirtualCouplingParams& p) {
  const Eigen::Vector3d phi = CalcRotationVector(X_WD.rotation * X_WH.rotation.conjugate());
  Matrix6d K = Matrix6d::Zero();
  K.topLeftCorner<3, 3>() = -p.k_vc * Eigen::Matrix3d::Identity();
  K.bottomRightCorner<3, 3>() = -p.k_vc_rot * CalcInverseRightJacobian(phi);
  return K;
}

VirtualCouplingParams CouplingAtRate(VirtualCouplingParams params, double cycle_seconds) {
  if (std::isfinite(cycle_seconds) && cycle_seconds > 0 && cycle_seconds != 1e-3)
    params.alpha = std::pow(params.alpha, cycle_seconds / 1e-3);
  return params;
}

StaticVirtualCoupling::StaticVirtualCoupling(const VirtualCouplingParams& params) : params_(params) {
  params_.Validate("virtual coupling parameters");
}

CouplingStep StaticVirtualCoupling::Update(const Pose& X_WD, const Wrench& contact_on_H, const Matrix6d& K_contact) {
  CouplingStep step;
  // Net wrench and stiffness of the first-order model, eqs. (5)-(6).
  const Wrench w_vc = CalcCouplingWrench(X_WD, X_WH_, params_);
  Vector6d w_net;
  w_net << w_vc.force + contact_on_H.force, w_vc.torque + contact_on_H.torque;
  const Matrix6d K = CalcCouplingSolveGradient(X_WD, X_WH_, params_) + K_contact;

  // Solve K delta = -w_net by LU with partial pivoting (fixed size: no allocation).
  lu_.compute(K);
  Vector6d delta = lu_.solve(-w_net);
  step.delta = delta;
  if (!delta.allFinite()) {
    step.solve_ok = false;
    delta.setZero();
  }

  // Quasi-static damping, then the per-cycle step bounds.
  Eigen::Vector3d dx = (1.0 - params_.alpha) * delta.head<3>();
  Eigen::Vector3d dtheta = (1.0 - params_.alpha) * delta.tail<3>();
  const double nx = dx.norm(), nt = dtheta.norm();
  if (nx > params_.max_step_translation) {
    dx *= params_.max_step_translation / nx;
    step.step_clamped = true;
  }
  if (nt > params_.max_step_rotation) {
    dtheta *= params_.max_step_rotation / nt;
    step.step_clamped = true;
  }

  // Move H and evaluate the coupling at the new pose: that is what the device renders.
  X_WH_.translation += dx;
  X_WH_.rotation = (RotationFromVector(dtheta) * X_WH_.rotation).normalized();
  step.X_WH = X_WH_;
  step.coupling_on_H = CalcCouplingWrench(X_WD, X_WH_, params_);
  step.to_device.force = -step.coupling_on_H.force;
  step.to_device.torque = -step.coupling_on_H.torque;
  return step;
}

}  // namespace contactlab
