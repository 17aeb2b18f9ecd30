// contactlab.Mesh from NumPy arrays (python/mesh_arrays.h).
#include "mesh_arrays.h"

#include <pybind11/numpy.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "argument_error.h"
#include "geometry/mesh_from_arrays.h"
#include "poses.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

std::string ShapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i > 0 ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string DtypeText(const py::array& a) { return py::str(py::object(a.dtype())).cast<std::string>(); }

// Fails naming WHERE unless A is a (rows, 3) array; WHAT names the array and its rows.
void ExpectRowsOf3(const py::array& a, const std::string& where, const std::string& what) {
  if (a.ndim() != 2 || a.shape(1) != 3) FailArgument(where, what + "; got shape " + ShapeText(a));
}

// The (T, 3) indices of A as int64, row-major. Integer dtypes convert as they are; floating ones
// only when every value is a whole number. NV: the vertex count, for the range message of an
// index too large for int64.
std::vector<std::int64_t> IndicesOf(const py::array& a, std::size_t nv, const std::string& where) {
  const char kind = a.dtype().kind();
  std::vector<std::int64_t> out(std::size_t(a.size()));
  auto out_of_range = [&](std::size_t i, const std::string& value) {
    FailArgument(where, "triangle " + std::to_string(i / 3) + ": face vertex index " + value + " out of range [0, " +
                            std::to_string(nv) + ")");
  };
  if (kind == 'u' && a.itemsize() == 8) {
    // uint64: the one integer dtype with values int64 cannot hold (all of them out of range).
    const auto u = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (u.data()[i] > std::uint64_t(std::numeric_limits<std::int64_t>::max())) out_of_range(i, std::to_string(u.data()[i]));
      out[i] = std::int64_t(u.data()[i]);
    }
  } else if (kind == 'i' || kind == 'u') {
    const auto v = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    std::copy(v.data(), v.data() + out.size(), out.begin());
  } else if (kind == 'f') {
    // Whole numbers only (np.loadtxt's float64 faces); 1.5 or NaN is no index.
    const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double x = v.data()[i];
      if (!std::isfinite(x) || std::trunc(x) != x) {
        throw py::type_error(where + ": triangles[" + std::to_string(i / 3) + "] holds " +
                             py::repr(py::float_(x)).cast<std::string>() +
                             ", not a whole number (vertex indices are integers)");
      }
      if (!(std::abs(x) < 9.2e18)) out_of_range(i, py::repr(py::float_(x)).cast<std::string>());
      out[i] = std::int64_t(x);
    }
  } else {
    throw py::type_error(where + ": triangles must be integer vertex indices (an array of int or uint); got dtype " +
                         DtypeText(a));
  }
  return out;
}

}  // namespace

Mesh MakeMesh(const py::object& vertices, const py::object& triangles, const std::string& name) {
  if (name.empty()) FailArgument("contactlab.Mesh", "name must not be empty (it names the mesh in messages and "
                                                    "is a body's default name)");
  const std::string where = "contactlab.Mesh '" + QuoteToken(name) + "'";
  // Vertices: real numbers as every converting call takes them (poses.h), (V, 3).
  const DoubleArray v = DoublesFromObject(vertices, where + ": vertices");
  ExpectRowsOf3(v, where, "vertices must be a (V, 3) array of x, y, z rows (metres)");
  // Triangles: (T, 3) integer indices.
  const py::array t = ArrayFromObject(triangles, where + ": triangles");
  ExpectRowsOf3(t, where, "triangles must be a (T, 3) array of vertex index rows");
  const std::vector<std::int64_t> indices = IndicesOf(t, std::size_t(v.shape(0)), where);
  try {
    return Mesh{std::make_shared<const TriangleMesh>(
        MeshFromArrays(std::span<const double>(v.data(), std::size_t(v.size())), indices, name, where))};
  } catch (const ArgumentError&) {
    throw;
  } catch (const Error& e) {
    throw ArgumentError(e.what());
  }
}

}  // namespace contactlab::python
