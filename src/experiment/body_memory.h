// Memory held by a body's contact data, counted from the arrays that hold it (summary.csv
// columns field_B_bytes and pointshell_A_bytes; experiments/scale-resolution.yaml).
#pragma once

#include <cstdint>

#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

// Bytes of FIELD's samples (DistanceField::memory_bytes): a dense field's float per grid point
// (dims.x * dims.y * dims.z of them); a sparse field's coarse grid, brick slots and stored
// bricks' 16-bit samples. The few scalars beside them (origin, spacing, bounds) are not counted.
std::int64_t FieldBytes(const DistanceField& field);

// Bytes of POINTSHELL's arrays: positions and normals per point, the level table, and per
// tree node its point, bounding radius, children range and parent. Its description strings
// (method, source) are not counted.
std::int64_t PointshellBytes(const Pointshell& pointshell);

}  // namespace contactlab
