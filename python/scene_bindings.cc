// contactlab.Scene and contactlab.Body: a scene read from YAML (scene/scene.h), its two
// bodies' meshes, distance fields and pointshells (scene/scene_assets.h) as NumPy arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "bindings.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "geometry/mesh_io.h"
#include "mesh_arrays.h"
#include "poses.h"
#include "scene_dict.h"
#include "scene_handle.h"
#include "util/config_node.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"

namespace py = pybind11;

namespace contactlab::python {

// Defined in model_bindings.cc: the Python Model of registered model NAME between the scene's
// bodies, its model section overridden by PARAMS.
py::object MakeModel(const std::shared_ptr<SceneHandle>& scene, const std::string& name, const py::kwargs& params);

namespace {

// One of a scene's two bodies (A: pointshell role, B: field role).
struct Body {
  std::shared_ptr<SceneHandle> scene;
  bool is_A = true;
  BodyAssets& assets() const { return is_A ? scene->assets.A : scene->assets.B; }
  const BodySpec& spec() const { return is_A ? scene->scene.pointshell_body : scene->scene.field_body; }
};

// A body's pointshell up to one tree level: (#P, 3) points and inward unit normals, body frame.
struct PointshellArrays {
  py::array_t<double> points, normals;
  int level = 0;
  int num_levels = 0;
};

// A read-only (rows, 3) view of the contiguous 3-vectors at DATA, kept alive by OWNER.
template <typename T>
py::array View3(const T* data, std::size_t rows, py::handle owner) {
  py::array a(py::dtype::of<T>(), {py::ssize_t(rows), py::ssize_t(3)}, {py::ssize_t(3 * sizeof(T)), py::ssize_t(sizeof(T))},
              data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

AssetOptions Options(const std::optional<std::string>& cache_dir, bool use_cache, bool verbose) {
  AssetOptions options;
  if (cache_dir) options.cache_dir = *cache_dir;
  options.use_cache = use_cache;
  options.verbose = verbose;
  return options;
}

PointshellArrays PointshellOf(Body& body, int level) {
  const std::shared_ptr<const Pointshell> shell = body.assets().pointshell();
  const int levels = shell->num_levels();
  if (level < -1 || level >= levels) {
    Fail(std::string(body.assets().body_name()) + ": pointshell level",
         std::to_string(level) + " is outside -1 (the deepest) to " + std::to_string(levels - 1));
  }
  const int l = level < 0 ? levels - 1 : level;
  const std::size_t n = std::size_t(shell->points_in_level(l));
  PointshellArrays out;
  out.points = py::array_t<double>({py::ssize_t(n), py::ssize_t(3)});
  out.normals = py::array_t<double>({py::ssize_t(n), py::ssize_t(3)});
  double* p = out.points.mutable_data();
  double* m = out.normals.mutable_data();
  for (std::size_t i = 0; i < n; ++i) {
    p[3 * i] = shell->x[i], p[3 * i + 1] = shell->y[i], p[3 * i + 2] = shell->z[i];
    m[3 * i] = shell->nx[i], m[3 * i + 1] = shell->ny[i], m[3 * i + 2] = shell->nz[i];
  }
  out.level = l;
  out.num_levels = levels;
  return out;
}

py::object DistanceOf(Body& body, py::handle points_object) {
  const std::string where = std::string(body.assets().body_name()) + ": distance(points)";
  const DoubleArray points = DoublesFromObject(points_object, where);
  const PointRows p_BQ = PointsFromArray(points, where);
  const std::shared_ptr<const DistanceField> field = body.assets().field();
  const py::ssize_t n = py::ssize_t(p_BQ.rows());
  py::array_t<double> d(n);
  double* out = d.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) out[i] = field->Distance(p_BQ.row(i).transpose());
  }
  if (points.ndim() == 1) return py::float_(out[0]);
  return d;
}

}  // namespace

void BindScene(py::module_& m) {
  py::class_<Mesh>(m, "Mesh",
                   "A triangle mesh in its body frame, metres: a body's (Body.mesh), or one made from arrays, "
                   "which Scene.from_dict takes as a body's mesh. Its arrays are read-only views.")
      .def(py::init(&MakeMesh), py::arg("vertices"), py::arg("triangles"), py::arg("name") = "mesh",
           "A mesh from arrays (copied): VERTICES (V, 3) real numbers, body frame, metres; TRIANGLES (T, 3) "
           "zero-based vertex indices, counter-clockwise seen from outside (an integer dtype, or a floating one "
           "holding whole numbers only); NAME names it in messages and is a body's default name. Polygon soups "
           "pass, as from a mesh file. Raises contactlab.ArgumentError (a ValueError) naming the mesh and the row "
           "for what the mesh file readers refuse: a coordinate that is not finite or beyond +-1e9 m, a negative "
           "or out-of-range index, no triangles; and for a wrong shape or an empty name. Raises TypeError for "
           "arrays that are not real numbers (complex, strings, None) or indices that are not whole numbers.")
      .def_property_readonly(
          "vertices", [](py::object self) { const Mesh& s = self.cast<const Mesh&>();
            return View3(s.mesh->vertices.empty() ? nullptr : s.mesh->vertices.front().data(), s.mesh->vertices.size(), self); },
          "(V, 3) float64 vertex positions, body frame, metres")
      .def_property_readonly(
          "triangles", [](py::object self) { const Mesh& s = self.cast<const Mesh&>();
            return View3(s.mesh->triangles.empty() ? nullptr : s.mesh->triangles.front().data(), s.mesh->triangles.size(), self); },
          "(T, 3) int32 vertex indices, counter-clockwise seen from outside")
      .def_property_readonly("name", [](const Mesh& s) { return s.mesh->name; })
      .def(
          "save",
          [](const Mesh& s, const std::string& path) {
            CheckOutputWritable(path, "Mesh.save");
            py::gil_scoped_release release;
            SaveMesh(*s.mesh, path);
          },
          py::arg("path"),
          "Writes the mesh to PATH as OBJ, OFF, STL or PLY by its extension (OBJ, OFF and PLY keep the "
          "coordinates exactly), atomically: a temporary file renamed onto PATH, nothing written on an error. "
          "A scene or experiment file can then name it as a body's mesh. Raises contactlab.Error naming PATH "
          "for an unknown extension, a special file or folder, or a failed write.")
      .def("__repr__", [](const Mesh& s) {
        return "<contactlab.Mesh " + s.mesh->name + ": " + std::to_string(s.mesh->num_vertices()) + " vertices, " +
               std::to_string(s.mesh->num_triangles()) + " triangles>";
      });

  py::class_<PointshellArrays>(m, "Pointshell",
                               "A body's pointshell up to one tree level; unpacks as (points, normals).")
      .def_readonly("points", &PointshellArrays::points, "(P, 3) float64 points, body frame, metres")
      .def_readonly("normals", &PointshellArrays::normals, "(P, 3) float64 inward unit normals, body frame")
      .def_readonly("level", &PointshellArrays::level, "the tree level these points make up (0 = coarsest)")
      .def_readonly("num_levels", &PointshellArrays::num_levels, "levels of the pointshell's tree")
      .def("__len__", [](const PointshellArrays& s) { return s.points.shape(0); })
      .def("__iter__", [](const PointshellArrays& s) { return py::iter(py::make_tuple(s.points, s.normals)); });

  py::class_<Body>(m, "Body", "One of a scene's two bodies: A (pointshell role) or B (field role).")
      .def_property_readonly("name", [](const Body& b) { return b.spec().name; })
      .def_property_readonly("role", [](const Body& b) { return b.spec().role; }, "'pointshell' (A) or 'field' (B)")
      .def_property_readonly("pose", [](const Body& b) { return PoseToArray(b.spec().pose); },
                             "the scene's pose of the body, (7,) x, y, z, qw, qx, qy, qz")
      .def_property_readonly("deformable", [](const Body& b) { return b.spec().deformable.has_value(); })
      .def_property_readonly("mesh", [](Body& b) { return Mesh{b.assets().mesh()}; },
                             "the body's triangle mesh (Mesh: vertices, triangles), body frame, metres")
      .def("distance", &DistanceOf, py::arg("points"),
           "Signed distances of POINTS, (N, 3) float64 in the body frame (metres), in the body's distance "
           "field: (N,) float64 (a float for one (3,) point), negative inside. Builds the field (through the cache) on first use. "
           "Raises contactlab.ArgumentError (a ValueError) naming the point when the shape is wrong or a coordinate "
           "is not finite or beyond +-1e9 m, TypeError when POINTS are not real numbers (complex, strings, None).")
      .def("pointshell", &PointshellOf, py::arg("level") = -1,
           "The body's pointshell up to tree level LEVEL (-1: the deepest): Pointshell with points and "
           "normals, (P, 3) float64 each, body frame. Builds it (through the cache) on first use.")
      .def("__repr__", [](const Body& b) { return "<contactlab.Body " + b.spec().name + " (" + b.spec().role + ")>"; });

  py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(
      m, "Scene", "Two bodies and the parameters of the contact models between them (a scene YAML file).")
      .def_static(
          "load",
          [](const std::string& path, std::optional<std::string> cache_dir, bool use_cache, bool verbose) {
            return std::make_shared<SceneHandle>(LoadScene(RequireDataFile(path)), Options(cache_dir, use_cache, verbose));
          },
          py::arg("path"), py::kw_only(), py::arg("cache_dir") = py::none(), py::arg("use_cache") = true,
          py::arg("verbose") = false,
          "Reads the scene file PATH (found through the data search path, as the command line does). "
          "Fields and pointshells are built on first use and cached in CACHE_DIR (default: the "
          "command's cache) unless USE_CACHE is False.")
      .def_static(
          "from_yaml",
          [](const std::string& text, std::optional<std::string> cache_dir, bool use_cache, bool verbose) {
            return std::make_shared<SceneHandle>(ParseScene(ConfigNode::LoadString(text, "<yaml text>")),
                                                 Options(cache_dir, use_cache, verbose));
          },
          py::arg("text"), py::kw_only(), py::arg("cache_dir") = py::none(), py::arg("use_cache") = true,
          py::arg("verbose") = false, "Reads a scene from YAML TEXT (meshes through the data search path).")
      .def_static(
          "from_dict",
          [](py::handle d, std::optional<std::string> cache_dir, bool use_cache, bool verbose) {
            return std::make_shared<SceneHandle>(SceneFromDict(d), Options(cache_dir, use_cache, verbose));
          },
          py::arg("d"), py::kw_only(), py::arg("cache_dir") = py::none(), py::arg("use_cache") = true,
          py::arg("verbose") = false,
          "A scene from D, dicts, lists and scalars in the structure of a scene YAML file (docs/scene-reference.md), "
          "checked as a file is. A body's mesh may be a file name, a procedural shape or a contactlab.Mesh; fields "
          "and pointshells of a Mesh are cached keyed by its content, as a file's are. Raises "
          "contactlab.ArgumentError (a ValueError) naming the key path (\"<dict>: bodies[0].field.resolution: ...\"), "
          "TypeError naming it for a value no YAML file could hold or a Mesh anywhere but a body's mesh.")
      .def_property_readonly("name", [](const SceneHandle& s) { return s.scene.name; })
      .def_property_readonly("file", [](const SceneHandle& s) { return s.scene.file; })
      .def_property_readonly("models", [](const SceneHandle& s) { return s.scene.models; },
                             "the model names the scene lists")
      .def_property_readonly("A", [](std::shared_ptr<SceneHandle> s) { return Body{s, true}; }, "body A (pointshell role)")
      .def_property_readonly("B", [](std::shared_ptr<SceneHandle> s) { return Body{s, false}; }, "body B (field role)")
      .def_property_readonly("bodies", [](std::shared_ptr<SceneHandle> s) { return py::make_tuple(Body{s, true}, Body{s, false}); },
                             "(A, B)")
      .def("model", &MakeModel, py::arg("name") = "",
           "Model NAME (default: the scene's first) between the scene's bodies; keyword arguments replace "
           "keys of the scene's model section (k_C=2000, L=10, node_budget=500, ...), each checked as in a "
           "scene file. Builds only what the model needs.")
      .def("__repr__", [](const SceneHandle& s) { return "<contactlab.Scene " + s.scene.name + ">"; });
}

}  // namespace contactlab::python
