// contactlab.World: a scene of many bodies (scene/scene_world.h) from Python: loaded from a file,
// YAML text or dicts (arrays as meshes), every pair queried in one call, per-pair results as
// NumPy arrays in the order of World.pairs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "argument_error.h"
#include "bindings.h"
#include "poses.h"
#include "scene/scene.h"
#include "scene/scene_world.h"
#include "scene_dict.h"
#include "util/data_path.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

struct WorldHandle {
  WorldHandle(const Scene& scene, const std::optional<std::string>& model, const AssetOptions& options)
      : world(Checked(scene), model ? *model : scene.models.front(), options) {}
  SceneWorld world;
  std::int64_t cycle = 0;

 private:
  static const Scene& Checked(const Scene& scene) {
    if (!scene.many_bodies()) {
      throw ArgumentError((scene.file.empty() ? std::string("scene") : scene.file) +
                          ": a World holds a scene of many bodies (with `tool:`); a scene of two bodies is a "
                          "contactlab.Scene");
    }
    return scene;
  }
};

AssetOptions WorldOptions(const std::optional<std::string>& cache_dir, bool use_cache, bool verbose) {
  AssetOptions options;
  if (cache_dir) options.cache_dir = *cache_dir;
  options.use_cache = use_cache;
  options.verbose = verbose;
  return options;
}

py::array_t<double> Rows3(int n) { return py::array_t<double>({py::ssize_t(n), py::ssize_t(3)}); }

py::dict Query(WorldHandle& h, py::object tool_pose, std::optional<std::int64_t> node_budget) {
  SceneWorld& w = h.world;
  Pose X = w.scene().bodies[std::size_t(w.tool())].pose;
  if (!tool_pose.is_none()) X = PoseFromArray(DoublesFromObject(tool_pose, "tool_pose"), "tool_pose");
  if (node_budget && *node_budget < 0) throw ArgumentError("node_budget: must be >= 0, got " + std::to_string(*node_budget));
  const WorldResult r = w.Evaluate(X, h.cycle++, node_budget ? *node_budget : -1);
  const int n = w.pair_count();
  py::array_t<double> force = Rows3(n), torque = Rows3(n);
  py::array_t<bool> near(n);
  py::array_t<std::int64_t> points(n), nodes(n), degraded(n), budget(n);
  auto f = force.mutable_unchecked<2>();
  auto t = torque.mutable_unchecked<2>();
  for (int p = 0; p < n; ++p) {
    const PairOutcome& o = w.outcome(p);
    for (int k = 0; k < 3; ++k) {
      f(p, k) = o.result.on_B.force[k];
      t(p, k) = o.result.on_B.torque[k];
    }
    near.mutable_at(p) = o.near;
    points.mutable_at(p) = o.result.stats.points_in_contact;
    nodes.mutable_at(p) = o.result.stats.nodes_visited;
    degraded.mutable_at(p) = o.result.stats.degraded;
    budget.mutable_at(p) = o.budget;
  }
  py::array_t<double> K({6, 6});
  auto k = K.mutable_unchecked<2>();
  for (int i = 0; i < 6; ++i) {
    for (int c = 0; c < 6; ++c) k(i, c) = r.K_tool(i, c);
  }
  py::array_t<double> F(3), T(3);
  for (int i = 0; i < 3; ++i) {
    F.mutable_at(i) = r.on_tool.force[i];
    T.mutable_at(i) = r.on_tool.torque[i];
  }
  py::dict d;
  d["force"] = F;
  d["torque"] = T;
  d["K_tool"] = K;
  d["pair_force"] = force;
  d["pair_torque"] = torque;
  d["near"] = near;
  d["points_in_contact"] = points;
  d["nodes_visited"] = nodes;
  d["degraded"] = degraded;
  d["node_budget"] = budget;
  d["pairs_near"] = r.stats.pairs_near;
  d["pairs_touching"] = r.stats.pairs_touching;
  return d;
}

}  // namespace

void BindWorld(py::module_& m) {
  py::class_<WorldHandle>(m, "World",
                          "A scene of many bodies (a tool among parts, docs/scenes.md \"Many bodies\"): one model per "
                          "pair, FCL's broad phase, one node budget for the cycle.")
      .def_static(
          "load",
          [](const std::string& path, std::optional<std::string> model, std::optional<std::string> cache_dir,
             bool use_cache, bool verbose) {
            return std::make_unique<WorldHandle>(LoadScene(RequireDataFile(path)), model,
                                                 WorldOptions(cache_dir, use_cache, verbose));
          },
          py::arg("path"), py::kw_only(), py::arg("model") = py::none(), py::arg("cache_dir") = py::none(),
          py::arg("use_cache") = true, py::arg("verbose") = false,
          "Reads the scene file PATH (through the data search path); MODEL (default: the scene's first) is every "
          "pair's that names none of its own. Builds each body's mesh and what its pairs' models need.")
      .def_static(
          "from_yaml",
          [](const std::string& text, std::optional<std::string> model, std::optional<std::string> cache_dir,
             bool use_cache, bool verbose) {
            return std::make_unique<WorldHandle>(ParseScene(ConfigNode::LoadString(text, "<yaml text>")), model,
                                                 WorldOptions(cache_dir, use_cache, verbose));
          },
          py::arg("text"), py::kw_only(), py::arg("model") = py::none(), py::arg("cache_dir") = py::none(),
          py::arg("use_cache") = true, py::arg("verbose") = false, "A World from YAML TEXT, as World.load.")
      .def_static(
          "from_dict",
          [](py::handle d, std::optional<std::string> model, std::optional<std::string> cache_dir, bool use_cache,
             bool verbose) {
            return std::make_unique<WorldHandle>(SceneFromDict(d), model, WorldOptions(cache_dir, use_cache, verbose));
          },
          py::arg("d"), py::kw_only(), py::arg("model") = py::none(), py::arg("cache_dir") = py::none(),
          py::arg("use_cache") = true, py::arg("verbose") = false,
          "A World from dicts in the structure of a scene file, a body's mesh optionally a contactlab.Mesh "
          "(arrays), checked as Scene.from_dict checks them.")
      .def_property_readonly("tool", [](const WorldHandle& h) { return h.world.scene().bodies[std::size_t(h.world.tool())].name; })
      .def_property_readonly(
          "bodies",
          [](const WorldHandle& h) {
            py::list names;
            for (const BodySpec& b : h.world.scene().bodies) names.append(b.name);
            return names;
          },
          "the body names, in the scene's order")
      .def_property_readonly(
          "pairs",
          [](const WorldHandle& h) {
            py::list pairs;
            const auto& bodies = h.world.scene().bodies;
            for (int p = 0; p < h.world.pair_count(); ++p) {
              const OrderedPair& o = h.world.pair(p);
              pairs.append(py::make_tuple(bodies[std::size_t(o.A)].name, bodies[std::size_t(o.B)].name));
            }
            return pairs;
          },
          "(A, B) names of each pair in its model's order: the rows of every per-pair array of query()")
      .def_property_readonly(
          "pair_models",
          [](const WorldHandle& h) {
            py::list names;
            for (int p = 0; p < h.world.pair_count(); ++p) names.append(h.world.pair(p).model);
            return names;
          },
          "each pair's model")
      .def_property_readonly(
          "built",
          [](WorldHandle& h) {
            py::dict built;
            for (int b = 0; b < h.world.body_count(); ++b) {
              built[py::str(h.world.scene().bodies[std::size_t(b)].name)] = h.world.body(b).Built();
            }
            return built;
          },
          "per body, what its pairs' models needed built (mesh, field, pointshell, reduced model, ...)")
      .def("query", &Query, py::arg("tool_pose") = py::none(), py::kw_only(), py::arg("node_budget") = py::none(),
           "One cycle with the tool at TOOL_POSE ((7,) or (4, 4); default: its scene pose), the other bodies at "
           "theirs, under NODE_BUDGET (default: the scene's) shared by the pairs near. Returns a dict: force, "
           "torque (3,) on the tool about its origin, K_tool (6, 6); per pair (rows as World.pairs): pair_force, "
           "pair_torque (P, 3) on the pair's B, near (P,) bool, points_in_contact, nodes_visited, degraded, "
           "node_budget (P,); pairs_near, pairs_touching. Each call is the next cycle of every pair's coherence.")
      .def("reset", [](WorldHandle& h) { h.world.Reset(); }, "Forgets every pair's temporal state.")
      .def("__repr__", [](const WorldHandle& h) {
        return "<contactlab.World " + h.world.scene().name + ": " + std::to_string(h.world.body_count()) +
               " bodies, " + std::to_string(h.world.pair_count()) + " pairs>";
      });
}

}  // namespace contactlab::python
