#include "view/field_slice.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "util/error.h"

namespace contactlab {

FieldSlice SliceField(const DistanceField& field, int axis, double at, int max_side) {
  if (field.empty()) Fail("field slice", "the distance field is empty");
  if (axis < 0 || axis > 2) Fail("field slice", "axis " + std::to_string(axis) + " is not 0, 1 or 2");
  FieldSlice s;
  s.axis = axis;
  const int a_u = (axis + 1) % 3, a_v = (axis + 2) % 3;
  const Eigen::Vector3d lo = field.origin();
  const Eigen::Vector3d hi = field.GridPoint(field.dims().x() - 1, field.dims().y() - 1, field.dims().z() - 1);
  s.at = std::clamp(at, lo[axis], hi[axis]);
  // Grid samples along U and V, every STEP-th one when the grid is larger than MAX_SIDE.
  const int nu = field.dims()[a_u], nv = field.dims()[a_v];
  const int step = std::max(1, (std::max(nu, nv) + std::max(1, max_side) - 1) / std::max(1, max_side));
  s.width = (nu - 1) / step + 1;
  s.height = (nv - 1) / step + 1;
  s.corner = lo;
  s.corner[axis] = s.at;
  s.u = Eigen::Vector3d::Zero();
  s.v = Eigen::Vector3d::Zero();
  s.u[a_u] = field.spacing() * step;
  s.v[a_v] = field.spacing() * step;
  s.values.resize(std::size_t(s.width) * s.height);
  for (int j = 0; j < s.height; ++j) {
    for (int i = 0; i < s.width; ++i) {
      s.values[std::size_t(j) * s.width + i] = float(field.Distance(s.corner + double(i) * s.u + double(j) * s.v));
    }
  }
  return s;
}

}  // namespace contactlab
