// K_B of the pressure-field model by forward differences of its wrench in B's pose
// (pressure_field_model.h): the derivative of the discretised surface of Elandt et al. 2019,
// up to O(step).
#pragma once

#include "contact/contact_model.h"
#include "geometry/pose.h"

namespace contactlab {

// B's pose X_WB moved along coordinate C of a world twist: C < 3 translates by STEP_X (metres)
// along world axis C, C >= 3 rotates by STEP_W (radians) about world axis C - 3.
Pose SteppedPose(const Pose& X_WB, int c, double step_x, double step_w);

// d(wrench on B)/d(pose of B) by forward differences: column C is (WRENCH_ON_B(SteppedPose(X_WB,
// C)) - W0) / step, with W0 the wrench at X_WB. WRENCH_ON_B: Pose -> Wrench (world frame).
template <class WrenchOnB>
Matrix6d ForwardDifferenceStiffness(const Pose& X_WB, const Vector6d& w0, double step_x, double step_w,
                                    WrenchOnB&& wrench_on_B) {
  Matrix6d K;
  for (int c = 0; c < 6; ++c) {
    const Pose X_WB_c = SteppedPose(X_WB, c, step_x, step_w);
    K.col(c) = (wrench_on_B(X_WB_c).AsVector() - w0) / (c < 3 ? step_x : step_w);
  }
  return K;
}

}  // namespace contactlab
