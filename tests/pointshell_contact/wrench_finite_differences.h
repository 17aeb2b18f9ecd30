// Central differences of a model's wrench on B with respect to B's pose (dx, dθ) in world
// coordinates, the convention of ContactResult::K_B: the independent reference the contact
// gradients are checked against.
#pragma once

#include "contact/contact_model.h"
#include "geometry/pose.h"

namespace contactlab::testing {

inline Matrix6d FiniteDifferenceGradient(ContactModel& model, ContactQuery q, double eps) {
  Matrix6d K;
  for (int c = 0; c < 6; ++c) {
    ContactQuery plus = q, minus = q;
    if (c < 3) {
      plus.X_WB.translation[c] += eps;
      minus.X_WB.translation[c] -= eps;
    } else {
      Eigen::Vector3d w = Eigen::Vector3d::Zero();
      w[c - 3] = eps;
      plus.X_WB.rotation = (RotationFromVector(w) * q.X_WB.rotation).normalized();
      minus.X_WB.rotation = (RotationFromVector(-w) * q.X_WB.rotation).normalized();
    }
    K.col(c) = (model.Evaluate(plus).on_B.AsVector() - model.Evaluate(minus).on_B.AsVector()) / (2 * eps);
  }
  return K;
}

}  // namespace contactlab::testing
