// Static virtual coupling with quasi-static damping (Barbič & James 2008, sec. 5; McNeely,
// Puterbaugh & Troy 2006): the simulated haptic body H is tied to the device manipulandum D by
// a saturating linear and rotational spring, and moved each cycle to the first-order static
// equilibrium of eqs. (5)-(6) between coupling and contact wrenches.
//
// Stiffness felt. With l contact points of stiffness k_C each in series with the coupling
// spring k_VC, the largest stiffness the user can feel is
//     k_felt = 1 / (1 / (l * k_C) + 1 / k_VC)  <  k_VC,
// so k_VC bounds the rendered stiffness whatever the number of points in contact; choose it
// below the device's maximum stable stiffness (HapticDevice::capabilities().max_stiffness).
//
// Frames and conventions. X_WD: device (manipulandum) pose in world; X_WH: simulated haptic
// body pose in world. Wrenches on H are about H's origin, world frame, ordered (force, torque).
// Gradients are d(wrench on H)/d(pose of H) for the perturbation
// X_WH -> (exp([dθ]) R_WH, p_WH + dx), (dx, dθ) in world coordinates — the convention of
// ContactResult::K_B in contact/contact_model.h, so the haptic body is the contact model's B.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include "contact/contact_model.h"
#include "geometry/pose.h"

namespace contactlab {

struct VirtualCouplingParams {
  double k_vc = 600.0;          // linear coupling stiffness, N/m
  double k_vc_rot = 1.0;        // rotational coupling stiffness, N m / rad
  double max_force = 8.0;       // coupling force saturation, N
  double max_torque = 0.4;      // coupling torque saturation, N m
  double alpha = 0.5;           // quasi-static damping in [0, 1): move by (1 - alpha) of the solve
                                // each cycle (a haptic cycle's: CouplingAtRate sets it from the
                                // paper's per-millisecond value)
  double max_step_translation = 0.01;  // safety bound on one cycle's move of H, m
  double max_step_rotation = 0.2;      // safety bound on one cycle's rotation of H, rad

  // Throws Error naming WHERE and the field when a value is non-finite or out of range.
  void Validate(const char* where) const;
};

// The coupling of a cycle of CYCLE_SECONDS from PARAMS whose alpha is the paper's, per 1 ms
// cycle: alpha^(CYCLE_SECONDS / 1 ms), so that H approaches the static equilibrium with the same
// time constant, 1 ms / ln(1 / alpha), at any rate (unchanged at 1 kHz; at 10 kHz 0.5 becomes
// 0.933). Without it H would follow the device ten times faster in time at 10 kHz, and a jump
// that takes H 1 ms at 1 kHz would take it 0.1 ms and outrun the contact model's coherence bound.
VirtualCouplingParams CouplingAtRate(VirtualCouplingParams params, double cycle_seconds);

// Coupling wrench on H (spring pulling H toward D), saturated to max_force / max_torque:
// F = k_vc (p_WD - p_WH), T = k_vc_rot * phi with phi the rotation vector of R_WD R_WH^T.
// Never throws, never allocates.
Wrench CalcCouplingWrench(const Pose& X_WD, const Pose& X_WH, const VirtualCouplingParams& p);

// The exact analytic gradient of CalcCouplingWrench with respect to H's pose (convention
// above), including the saturated branches: 6x6, blocks [dF/dx 0; 0 dT/dθ].
Matrix6d CalcCouplingGradient(const Pose& X_WD, const Pose& X_WH, const VirtualCouplingParams& p);

// The gradient used in the equilibrium solve: the linear-region spring gradient
// (-k_vc I and -k_vc_rot J_r^{-1}(phi)) even when the coupling saturates. The exact saturated
// gradient has a zero eigenvalue along the spring, which leaves free-space motion undetermined;
// with the linear-region gradient a saturated coupling moves H by at most
// (1 - alpha) max_force / k_vc per cycle toward D, like a virtual proxy.
Matrix6d CalcCouplingSolveGradient(const Pose& X_WD, const Pose& X_WH, const VirtualCouplingParams& p);

// What one coupling update produced.
struct CouplingStep {
  Pose X_WH;                 // new simulated pose of H
  Wrench coupling_on_H;      // coupling wrench on H at the new pose
  Wrench to_device;          // wrench to render: -coupling_on_H (about D's origin)
  Vector6d delta = Vector6d::Zero();  // undamped solve (dx, dθ) before alpha and step bounds
  bool solve_ok = true;      // false when the solve was non-finite and H was not moved
  bool step_clamped = false; // true when a step bound limited the move
};

// One cycle of static virtual coupling with quasi-static damping. Holds the simulated pose of
// H between cycles. Allocation-free and exception-free in Update().
class StaticVirtualCoupling {
 public:
  // Throws Error when PARAMS is invalid.
  explicit StaticVirtualCoupling(const VirtualCouplingParams& params);

  const VirtualCouplingParams& params() const { return params_; }
  const Pose& X_WH() const { return X_WH_; }
  // Places H (e.g. at the device pose at session start).
  void Reset(const Pose& X_WH) { X_WH_ = X_WH; }

  // Solves (K_VC + K_C) delta = -(W_VC + W_C) by LU (6x6, partial pivoting), moves H by
  // (1 - alpha) delta (bounded by the step limits), and returns the coupling wrench at the new
  // pose. CONTACT_ON_H and K_CONTACT come from a ContactModel evaluated at X_WH() (H as body B).
  CouplingStep Update(const Pose& X_WD, const Wrench& contact_on_H, const Matrix6d& K_contact);

 private:
  VirtualCouplingParams params_;
  Pose X_WH_;
  Eigen::PartialPivLU<Matrix6d> lu_;
};

}  // namespace contactlab
