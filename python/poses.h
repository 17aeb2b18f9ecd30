// Poses and point arrays from NumPy: a pose is a 7-vector (x, y, z, qw, qx, qy, qz; metres, a
// quaternion normalised as the command line's --pose-a does) or a 4x4 homogeneous matrix
// (rotation block orthonormal with determinant +1, last row 0 0 0 1).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "geometry/pose.h"

namespace contactlab::python {

using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

// One pose from a (7,) or (4, 4) array. Throws Error naming WHERE when the shape is neither,
// a value is not finite, the quaternion is zero or the matrix is no rigid transform.
Pose PoseFromArray(const DoubleArray& a, const std::string& where);

// N poses from an (N, 7) or (N, 4, 4) array, or one pose (7,) / (4, 4) as a batch of one.
std::vector<Pose> PosesFromArray(const DoubleArray& a, const std::string& where);

// POSE as the 7-vector (x, y, z, qw, qx, qy, qz).
pybind11::array_t<double> PoseToArray(const Pose& pose);

}  // namespace contactlab::python
