// K_B of the pressure field from its sums' derivatives (pressure_stiffness.h).
#include "baselines/pressure_field/pressure_stiffness.h"

#include "geometry/rotation_math.h"

namespace contactlab {

Matrix6d PressureStiffnessOnB(const Matrix6d& D, const Wrench& on_B, bool lattice_is_A, const Pose& X_WA,
                              const Pose& X_WB) {
  // The sums' derivatives in the world: L's frame turned to the world on both sides.
  const Eigen::Matrix3d R = (lattice_is_A ? X_WA : X_WB).R();
  Matrix6d RR = Matrix6d::Zero();
  RR.topLeftCorner<3, 3>() = R;
  RR.bottomRightCorner<3, 3>() = R;
  const Matrix6d DW = RR * D * RR.transpose();
  Matrix6d K;
  if (!lattice_is_A) {
    // F = R s_F and τ = R s_τ, R turning with B: a rotation w adds w × F and w × τ.
    K = DW;
    K.block<3, 3>(0, 3) -= Skew(on_B.force);
    K.block<3, 3>(3, 3) -= Skew(on_B.torque);
    return K;
  }
  // F = -F_A and τ = -(τ_A + (p_A - p_B) × F_A), F_A = R s_F: B's translation v moves p_B, which
  // adds v × F_A = -v × F to τ.
  const Eigen::Vector3d r = X_WA.translation - X_WB.translation;
  K.topRows<3>() = -DW.topRows<3>();
  K.bottomRows<3>() = -DW.bottomRows<3>() - Skew(r) * DW.topRows<3>();
  K.block<3, 3>(3, 0) += Skew(on_B.force);
  return K;
}

}  // namespace contactlab
