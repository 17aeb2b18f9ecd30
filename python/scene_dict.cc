// Scene.from_dict (python/scene_dict.h): Python values turned into the YAML node tree a scene
// file parses to, then parsed by ParseScene as a file is, with the in-memory meshes attached.
#include "scene_dict.h"

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "argument_error.h"
#include "mesh_arrays.h"
#include "util/config_node.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

// The source name of a dict in error messages, as a file name is for a scene file.
constexpr const char* kSource = "<dict>";
// Deeper nesting than any scene has: a list that contains itself fails here, not by recursion.
constexpr int kMaxDepth = 32;

std::string TypeName(py::handle obj) { return py::str(py::type::handle_of(obj).attr("__name__")).cast<std::string>(); }

// The body index I when PATH is "bodies[I].mesh", else -1.
long BodyOfMeshPath(const std::string& path) {
  const std::string head = "bodies[", tail = "].mesh";
  if (path.size() <= head.size() + tail.size() || path.rfind(head, 0) != 0 ||
      path.compare(path.size() - tail.size(), tail.size(), tail) != 0) {
    return -1;
  }
  const std::string digits = path.substr(head.size(), path.size() - head.size() - tail.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return -1;
  return std::stol(digits);
}

// Python values to YAML nodes, collecting the in-memory meshes of the bodies.
class DictToYaml {
 public:
  // (body index, mesh) of every body whose mesh is a contactlab.Mesh.
  std::vector<std::pair<std::size_t, std::shared_ptr<const TriangleMesh>>> meshes;

  YAML::Node Convert(py::handle obj, const std::string& path, int depth) {
    if (depth > kMaxDepth) Fail(path, "nested more than " + std::to_string(kMaxDepth) + " levels deep");
    const py::module_ numpy = py::module_::import("numpy");
    // NumPy arrays and scalars as the lists and Python scalars they hold.
    if (py::isinstance(obj, numpy.attr("ndarray")) || py::isinstance(obj, numpy.attr("generic"))) {
      return Convert(obj.attr("tolist")(), path, depth + 1);
    }
    const long body = BodyOfMeshPath(path);
    if (py::isinstance<Mesh>(obj)) {
      if (body < 0) {
        FailType(path, "a contactlab.Mesh is taken only as a body's mesh (bodies[i].mesh)");
      }
      const Mesh& m = obj.cast<const Mesh&>();
      meshes.emplace_back(std::size_t(body), m.mesh);
      return YAML::Node(m.mesh->name);  // names the mesh; the body's default name
    }
    if (body >= 0 && !py::isinstance<py::str>(obj)) {
      FailType(path, "expected a mesh file name, a procedural shape such as \"sphere:0.05\", or a contactlab.Mesh; got " +
                         TypeName(obj));
    }
    if (obj.is_none()) return YAML::Node(YAML::NodeType::Null);
    if (py::isinstance<py::bool_>(obj)) return YAML::Node(obj.cast<bool>() ? "true" : "false");
    if (py::isinstance<py::str>(obj)) return YAML::Node(obj.cast<std::string>());
    // Numbers as their Python text: an int exactly, a float as repr (it reads back as the same double).
    if (py::isinstance<py::int_>(obj)) return YAML::Node(py::str(obj).cast<std::string>());
    if (py::isinstance<py::float_>(obj)) return YAML::Node(py::repr(obj).cast<std::string>());
    if (py::isinstance<py::dict>(obj) || py::isinstance(obj, py::module_::import("collections.abc").attr("Mapping"))) {
      YAML::Node map(YAML::NodeType::Map);
      for (const py::handle key : obj.attr("keys")()) {
        if (!py::isinstance<py::str>(key)) {
          FailType(path, "keys are names (str); got the key " + py::repr(key).cast<std::string>());
        }
        const std::string k = key.cast<std::string>();
        map[k] = Convert(obj[key], path.empty() ? k : path + "." + k, depth + 1);
      }
      return map;
    }
    if (py::isinstance<py::list>(obj) || py::isinstance<py::tuple>(obj)) {
      YAML::Node seq(YAML::NodeType::Sequence);
      std::size_t i = 0;
      for (const py::handle e : obj) seq.push_back(Convert(e, path + "[" + std::to_string(i++) + "]", depth + 1));
      return seq;
    }
    FailType(path, "expected a dict, list, tuple, str, bool, int, float, NumPy array or None; got " + TypeName(obj));
  }

 private:
  static std::string Where(const std::string& path) {
    return std::string(kSource) + ": " + (path.empty() ? std::string("(top level)") : path);
  }
  [[noreturn]] static void Fail(const std::string& path, const std::string& what) { FailArgument(Where(path), what); }
  [[noreturn]] static void FailType(const std::string& path, const std::string& what) {
    throw py::type_error(Where(path) + ": " + what);
  }
};

}  // namespace

Scene SceneFromDict(py::handle d) {
  if (!py::isinstance<py::dict>(d) && !py::isinstance(d, py::module_::import("collections.abc").attr("Mapping"))) {
    throw py::type_error("Scene.from_dict: expected a dict in the structure of a scene YAML file; got " + TypeName(d));
  }
  DictToYaml converter;
  const YAML::Node root = converter.Convert(d, "", 0);
  Scene scene;
  try {
    scene = ParseScene(ConfigNode(root, std::make_shared<const std::string>(kSource), ""));
  } catch (const ArgumentError&) {
    throw;
  } catch (const Error& e) {
    throw ArgumentError(e.what());  // the dict is the call's argument
  }
  // Each in-memory mesh to the body that names it: a scene of many bodies keeps them in order, a
  // two-body scene's parse placed them by role.
  for (const auto& [i, mesh] : converter.meshes) {
    if (scene.many_bodies()) {
      scene.bodies[std::size_t(i)].mesh_data = mesh;
      continue;
    }
    const std::string role = root["bodies"][i]["role"].Scalar();
    (role == "pointshell" ? scene.pointshell_body : scene.field_body).mesh_data = mesh;
  }
  if (scene.many_bodies()) {  // the two-body fields' copies of the tool and another body (scene/scene.h)
    scene.field_body = scene.bodies[std::size_t(scene.tool)];
    scene.pointshell_body = scene.bodies[std::size_t(scene.tool == 0 ? 1 : 0)];
  }
  return scene;
}

}  // namespace contactlab::python
