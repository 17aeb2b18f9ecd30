// Exact point-triangle distances for many points against one triangle at a time, several points
// per instruction (Google Highway, run-time dispatch as sdf/batch_distance.h): the inner loop
// of the sparse field's builder (sdf/sparse_field.h), which tests every fine sample near a
// triangle against it.
#pragma once

namespace contactlab {

// OUT[i] = PointTriangleDistanceSquared((X[i], Y[i], Z[i]), A, B, C) for i in [0, N)
// (sdf/point_triangle_distance.h), to double rounding: the same regions (Ericson, Real-Time
// Collision Detection, sec. 5.1.5) chosen by masks instead of branches. TRI: 9 doubles (A, B, C).
// The triangle must not be degenerate (a non-zero normal); callers use the scalar function for
// those. Never allocates or throws.
void PointsTriangleDistancesSquared(const double* tri, const double* x, const double* y, const double* z, int n,
                                    double* out);

}  // namespace contactlab
