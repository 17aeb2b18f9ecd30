// Poses and point arrays from NumPy: a pose is a 7-vector (x, y, z, qw, qx, qy, qz; metres, a
// unit quaternion within 1e-6 as the command line's --pose-a needs, NonUnitQuaternionError) or a 4x4 homogeneous matrix
// (rotation block orthonormal with determinant +1, last row 0 0 0 1); a point is a 3-vector. The
// one conversion of every pose and point a Python call takes: no value that is not finite passes.
#pragma once

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "argument_error.h"
#include "geometry/pose.h"

namespace contactlab::python {

// float64, C-contiguous and aligned (a view of a byte buffer at an odd offset is copied: the
// conversion reads it through double pointers).
using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast |
                                                  pybind11::detail::npy_api::NPY_ARRAY_ALIGNED_>;

// OBJ as NumPy reads it (np.asarray, no copy of an array). Throws ArgumentError naming WHERE when
// NumPy refuses it with a ValueError (a ragged list), TypeError for its other refusals.
pybind11::array ArrayFromObject(pybind11::handle obj, const std::string& where);

// OBJ (an array, a nested list or tuple, a scalar, anything NumPy's asarray takes) as a float64
// C-contiguous array, converted as np.asarray(OBJ).astype(np.float64) would, of real numbers only:
// bool, integer and floating dtypes pass; complex, strings, datetimes, objects (None) and
// structured arrays raise TypeError naming WHERE (forcecast would drop an imaginary part, parse
// '1.5' and count days as metres). Throws ArgumentError naming WHERE when NumPy refuses OBJ as an
// array (a ragged list). Any shape passes; the callers check theirs.
DoubleArray DoublesFromObject(pybind11::handle obj, const std::string& where);

// (N, 3) points, row-major, viewing the array's data (no copy).
using PointRows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;

// The points of an (N, 3) array, or of one (3,) point as N = 1 (metres, in the frame the call
// names). Throws ArgumentError naming WHERE when the shape is neither or a coordinate is not
// finite or beyond kMaxCoordinate (geometry/triangle_mesh.h). The view lives as long as A.
PointRows PointsFromArray(const DoubleArray& a, const std::string& where);

// One pose from a (7,) or (4, 4) array. Throws ArgumentError naming WHERE when the shape is neither,
// a value is not finite, the quaternion is not unit length or the matrix is no rigid transform.
Pose PoseFromArray(const DoubleArray& a, const std::string& where);

// N poses from an (N, 7) or (N, 4, 4) array, or one pose (7,) / (4, 4) as a batch of one
// (N = 0 allowed). Throws ArgumentError as PoseFromArray, WHERE[i] naming the pose.
std::vector<Pose> PosesFromArray(const DoubleArray& a, const std::string& where);

// POSE as the 7-vector (x, y, z, qw, qx, qy, qz).
pybind11::array_t<double> PoseToArray(const Pose& pose);

}  // namespace contactlab::python
