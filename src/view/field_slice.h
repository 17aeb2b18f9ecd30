// One plane of a body's signed distance field for the viewer (Barbič & James 2008, sec. 2.3):
// an axis-aligned slice through the field's grid box, sampled by the field's own trilinear
// interpolation, body frame.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sdf/distance_field.h"

namespace contactlab {

struct FieldSlice {
  int axis = 2;                 // normal of the plane: 0 x, 1 y, 2 z (body frame)
  double at = 0;                // the plane's coordinate along AXIS, metres
  int width = 0, height = 0;    // samples along U and V
  Eigen::Vector3d corner;       // body frame position of sample (0, 0), metres
  Eigen::Vector3d u, v;         // body frame step between neighbouring samples along U and V
  std::vector<float> values;    // (height x width) signed distances, U fastest, metres
};

// The slice of FIELD normal to AXIS (0..2) at coordinate AT (clamped into the grid box),
// sampled on the field's grid along the two other axes (U = the next axis, V = the one after,
// cyclically), thinned to at most MAX_SIDE samples per side. Throws Error for an empty field
// or AXIS outside 0..2.
FieldSlice SliceField(const DistanceField& field, int axis, double at, int max_side = 512);

}  // namespace contactlab
