// The poses of the pressure field's forward differences (pressure_stiffness.h).
#include "baselines/pressure_field/pressure_stiffness.h"

namespace contactlab {

Pose SteppedPose(const Pose& X_WB, int c, double step_x, double step_w) {
  Pose X_WB_c = X_WB;
  if (c < 3) {
    X_WB_c.translation[c] += step_x;
  } else {
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    w[c - 3] = step_w;
    X_WB_c.rotation = (RotationFromVector(w) * X_WB_c.rotation).normalized();
  }
  return X_WB_c;
}

}  // namespace contactlab
