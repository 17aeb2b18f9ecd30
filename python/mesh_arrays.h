// contactlab.Mesh: a triangle mesh held by Python, either a body's (read-only views of what the
// scene loaded) or one made from another tool's NumPy arrays (geometry/mesh_from_arrays.h),
// which Scene.from_dict takes as a body's mesh.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "geometry/triangle_mesh.h"

namespace contactlab::python {

struct Mesh {
  std::shared_ptr<const TriangleMesh> mesh;
};

// The mesh NAME of VERTICES, (V, 3) real numbers (metres), and TRIANGLES, (T, 3) zero-based
// vertex indices of an integer dtype, or of a floating one holding whole numbers only (as
// np.loadtxt reads them), or nested lists of either. Raises TypeError for other types (complex,
// strings, objects, bool indices, an index that is not a whole number) and ArgumentError naming
// the mesh and the row for what the mesh readers refuse (a coordinate that is not finite or
// beyond +-1e9 m, a negative or out-of-range index, no triangles), a wrong shape or an empty name.
Mesh MakeMesh(const pybind11::object& vertices, const pybind11::object& triangles, const std::string& name);

}  // namespace contactlab::python
