// Poses and points from NumPy arrays (python/poses.h).
#include "poses.h"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "geometry/triangle_mesh.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

std::string ShapeText(const DoubleArray& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) {
    if (i > 0) s += ", ";
    s += std::to_string(a.shape(i));
  }
  s += a.ndim() == 1 ? ",)" : ")";
  return s;
}

// The pose of the 7 numbers at V, as ParsePose reads them from a command line.
Pose PoseFrom7(const double* v, const std::string& where) {
  for (int i = 0; i < 7; ++i) {
    if (!std::isfinite(v[i])) FailArgument(where, "pose component " + std::to_string(i) + " is not finite");
  }
  const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
  if (const std::optional<std::string> e = NonUnitQuaternionError(q)) FailArgument(where, *e);
  return {UnitQuaternion(q), Eigen::Vector3d(v[0], v[1], v[2])};
}

// The pose of the row-major 4x4 matrix at V.
Pose PoseFrom4x4(const double* v, const std::string& where) {
  Eigen::Matrix4d X;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) X(r, c) = v[4 * r + c];
  }
  if (!X.allFinite()) FailArgument(where, "pose matrix has a value that is not finite");
  if ((X.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-12) {
    FailArgument(where, "pose matrix: the last row must be 0 0 0 1");
  }
  // Written so that a NaN fails (R^T R of huge finite entries can overflow to inf - inf) without
  // relying on Eigen's maxCoeff, which may skip a NaN.
  const Eigen::Matrix3d R = X.topLeftCorner<3, 3>();
  const Eigen::Matrix3d E = R.transpose() * R - Eigen::Matrix3d::Identity();
  const bool orthonormal = (E.array().abs() <= 1e-6).all();
  if (!orthonormal || !(R.determinant() > 0)) {
    FailArgument(where, "pose matrix: the upper-left 3x3 block is not a rotation (orthonormal, determinant +1)");
  }
  return {Eigen::Quaterniond(R).normalized(), X.topRightCorner<3, 1>()};
}

// The dtype kinds NumPy converts to float64 without losing meaning: bool, signed and unsigned
// integers, floating point.
bool IsRealKind(char kind) { return kind == 'b' || kind == 'i' || kind == 'u' || kind == 'f'; }

}  // namespace

py::array ArrayFromObject(py::handle obj, const std::string& where) {
  if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
  // Lists, tuples, scalars, buffers and objects with __array__, as NumPy reads them.
  try {
    return py::module_::import("numpy").attr("asarray")(obj);
  } catch (py::error_already_set& e) {
    // KeyboardInterrupt, SystemExit and MemoryError pass as they are.
    if (!e.matches(PyExc_Exception) || e.matches(PyExc_MemoryError)) throw;
    if (e.matches(PyExc_ValueError)) FailArgument(where, std::string("not an array of numbers: ") + e.what());
    throw py::type_error(where + ": not an array of numbers: " + e.what());
  }
}

DoubleArray DoublesFromObject(py::handle obj, const std::string& where) {
  const py::array a = ArrayFromObject(obj, where);
  const py::dtype dtype = a.dtype();
  if (!IsRealKind(dtype.kind())) {
    throw py::type_error(where + ": expected real numbers (an array of float, int or bool); got dtype " +
                         py::str(py::object(dtype)).cast<std::string>() + " from " +
                         py::str(py::type::handle_of(obj)).cast<std::string>());
  }
  DoubleArray out = DoubleArray::ensure(a);
  if (!out) throw py::type_error(where + ": cannot be converted to float64");
  return out;
}

PointRows PointsFromArray(const DoubleArray& a, const std::string& where) {
  const bool one = a.ndim() == 1 && a.shape(0) == 3;
  if (!one && !(a.ndim() == 2 && a.shape(1) == 3)) {
    FailArgument(where, "points must be an (N, 3) array (body frame, metres); got shape " + ShapeText(a));
  }
  const PointRows points(a.data(), one ? 1 : a.shape(0), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const std::string point = one ? std::string("points") : "points[" + std::to_string(i) + "]";
    if (!points.row(i).allFinite()) FailArgument(where, point + " has a coordinate that is not finite");
    // Beyond the bound of every coordinate (a field's float lookup gave +inf from about 2e19 m).
    if (points.row(i).cwiseAbs().maxCoeff() > kMaxCoordinate) {
      FailArgument(where, point + " has a coordinate beyond the limit of +-1e9 m");
    }
  }
  return points;
}

Pose PoseFromArray(const DoubleArray& a, const std::string& where) {
  if (a.ndim() == 1 && a.shape(0) == 7) return PoseFrom7(a.data(), where);
  if (a.ndim() == 2 && a.shape(0) == 4 && a.shape(1) == 4) return PoseFrom4x4(a.data(), where);
  FailArgument(where, "a pose is a 7-vector (x, y, z, qw, qx, qy, qz) or a 4x4 matrix; got shape " + ShapeText(a));
}

std::vector<Pose> PosesFromArray(const DoubleArray& a, const std::string& where) {
  std::vector<Pose> poses;
  if ((a.ndim() == 1 && a.shape(0) == 7) || (a.ndim() == 2 && a.shape(0) == 4 && a.shape(1) == 4)) {
    poses.push_back(PoseFromArray(a, where));
  } else if (a.ndim() == 2 && a.shape(1) == 7) {
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
      poses.push_back(PoseFrom7(a.data() + 7 * i, where + "[" + std::to_string(i) + "]"));
    }
  } else if (a.ndim() == 3 && a.shape(1) == 4 && a.shape(2) == 4) {
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
      poses.push_back(PoseFrom4x4(a.data() + 16 * i, where + "[" + std::to_string(i) + "]"));
    }
  } else {
    FailArgument(where, "poses are an (N, 7) array of (x, y, z, qw, qx, qy, qz) rows or an (N, 4, 4) array of "
                        "matrices; got shape " + ShapeText(a));
  }
  return poses;
}

py::array_t<double> PoseToArray(const Pose& pose) {
  py::array_t<double> out(7);
  double* v = out.mutable_data();
  v[0] = pose.translation.x(), v[1] = pose.translation.y(), v[2] = pose.translation.z();
  v[3] = pose.rotation.w(), v[4] = pose.rotation.x(), v[5] = pose.rotation.y(), v[6] = pose.rotation.z();
  return out;
}

}  // namespace contactlab::python
