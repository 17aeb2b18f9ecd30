// The pose of the pointshell body A in the field body B's frame as float arrays, for the
// per-point loops of the point-based contact models (Barbič & James 2008, sec. 3; VPS).
#pragma once

#include "geometry/pose.h"

namespace contactlab {

struct FloatTransform {
  float r[9];  // R_BA, row-major
  float t[3];  // p_BA
  explicit FloatTransform(const Pose& X_BA) {
    const Eigen::Matrix3d R = X_BA.R();
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) r[3 * i + j] = float(R(i, j));
      t[i] = float(X_BA.translation[i]);
    }
  }
  // out = R_BA p + p_BA.
  void Apply(float x, float y, float z, float* out) const {
    out[0] = r[0] * x + r[1] * y + r[2] * z + t[0];
    out[1] = r[3] * x + r[4] * y + r[5] * z + t[1];
    out[2] = r[6] * x + r[7] * y + r[8] * z + t[2];
  }
  // out = R_BA v.
  void Rotate(float x, float y, float z, float* out) const {
    out[0] = r[0] * x + r[1] * y + r[2] * z;
    out[1] = r[3] * x + r[4] * y + r[5] * z;
    out[2] = r[6] * x + r[7] * y + r[8] * z;
  }
};

}  // namespace contactlab
