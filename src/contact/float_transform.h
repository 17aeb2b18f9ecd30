// The pose X_BA of the pointshell body A in the field body B's frame as float arrays, for the
// per-point loops of the point-based contact models (Barbič & James 2008, sec. 3; VPS):
// X_BA.Apply(p_AQ) is p_BQ, X_BA.Rotate(n_A) is n_B.
#pragma once

#include "geometry/pose.h"
#include "sdf/batch_distance.h"

namespace contactlab {

// The same 12 floats as the batched lookups' BatchTransform (sdf/batch_distance.h), so a
// FloatTransform is passed to them as it is.
struct FloatTransform : BatchTransform {
  explicit FloatTransform(const Pose& X_BA) {
    const Eigen::Matrix3d R = X_BA.R();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) r[3 * i + j] = float(R(i, j));
      t[i] = float(X_BA.translation[i]);
    }
  }
  // p_BQ = R_BA p_AQ + p_BA, for p_AQ = (x, y, z).
  void Apply(float x, float y, float z, float* out) const {
    out[0] = r[0] * x + r[1] * y + r[2] * z + t[0];
    out[1] = r[3] * x + r[4] * y + r[5] * z + t[1];
    out[2] = r[6] * x + r[7] * y + r[8] * z + t[2];
  }
  // v_B = R_BA v_A, for v_A = (x, y, z).
  void Rotate(float x, float y, float z, float* out) const {
    out[0] = r[0] * x + r[1] * y + r[2] * z;
    out[1] = r[3] * x + r[4] * y + r[5] * z;
    out[2] = r[6] * x + r[7] * y + r[8] * z;
  }
};

}  // namespace contactlab
