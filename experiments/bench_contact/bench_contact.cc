// Question: how long does one haptic cycle of the paper's contact model take, against
// pointshell size, for the tree-less (linear) traversal, the tree, the tree with temporal
// coherence, and the tree with coherence under a node budget (graceful degradation), on real
// mesh pairs in shallow and in deep contact? (Barbič & James 2008, sec. 3 and Table 1.)
//
// Each iteration is one cycle: body A slides on a 1 mm circle (6 mm/s) across B's surface
// while held at the placement depth, so coherence sees a moving configuration. Counters:
// ns_per_point (linear), nodes (visited per cycle), contacts, level, max_us (slowest cycle).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_common.h"
#include "contact/pointshell_contact_model.h"
#include "experiment/contact_placement.h"
#include "experiment/model_factory.h"
#include "experiment/scene.h"
#include "experiment/scene_assets.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

struct Prepared {
  Scene scene;
  std::unique_ptr<SceneAssets> assets;
  Pose X_WB;
  Pose X_WA[2];  // shallow, deep
  Eigen::Vector3d direction;
  bool ok = false;
};

constexpr double kDepths[2] = {0.0005, 0.002};  // shallow 0.5 mm, deep 2 mm
const char* kDepthNames[2] = {"shallow", "deep"};

Prepared& Prepare(const std::string& scene_file, int points, int levels) {
  static std::map<std::string, Prepared> cache;
  const std::string key = scene_file + "/" + std::to_string(points);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Prepared& p = cache[key];
  p.scene = LoadScene(RequireDataFile(scene_file));
  p.scene.pointshell_body.pointshell.points = points;
  p.scene.pointshell_body.pointshell.levels = levels;
  AssetOptions options;
  options.verbose = false;
  p.assets = std::make_unique<SceneAssets>(p.scene, options);
  p.X_WB = p.scene.field_body.pose;
  // Approach from the scene's start pose of A toward B's origin.
  const Pose start = p.scene.pointshell_body.pose;
  p.direction = (p.X_WB.translation - start.translation).normalized();
  PointshellContactParams params = PointshellParamsFromScene(p.scene);
  PointshellContactModel probe(PointshellContactModel::Variant::kLinear, p.assets->A.pointshell(), p.assets->B.field(),
                               params);
  Pose far = start;
  far.translation -= 0.05 * p.direction;
  p.ok = true;
  for (int d = 0; d < 2; ++d) {
    const Placement placed = PlaceAtDepth(probe, far, p.X_WB, p.direction, kDepths[d], 0.3);
    p.ok = p.ok && placed.found;
    p.X_WA[d] = placed.X_WA;
  }
  return p;
}

enum Variant { kLinear, kTree, kTreeCoherence, kTreeCoherenceBudget };
const char* kVariantNames[] = {"linear", "tree", "tree+coherence", "tree+coherence+budget"};

void BM_ContactCycle(benchmark::State& state, std::string scene_file, int points, int levels, Variant variant,
                     int depth, long long budget) {
  Prepared& p = Prepare(scene_file, points, levels);
  if (!p.ok) {
    state.SkipWithError("could not place the bodies in contact");
    return;
  }
  PointshellContactParams params = PointshellParamsFromScene(p.scene);
  params.coherence = variant >= kTreeCoherence;
  params.max_point_speed = 0.5;
  PointshellContactModel model(variant == kLinear ? PointshellContactModel::Variant::kLinear
                                                  : PointshellContactModel::Variant::kTree,
                               p.assets->A.pointshell(), p.assets->B.field(), params);
  // A circle in the plane perpendicular to the approach direction.
  const Eigen::Vector3d e1 = p.direction.unitOrthogonal(), e2 = p.direction.cross(e1);
  ContactQuery q;
  q.X_WB = p.X_WB;
  q.node_budget = variant == kTreeCoherenceBudget ? budget : 0;
  std::int64_t cycle = 0;
  double max_us = 0, nodes = 0, contacts = 0, level = 0;
  for (auto _ : state) {
    const double angle = 2 * M_PI * double(cycle) / 1000.0;  // one turn per second
    q.X_WA = p.X_WA[depth];
    q.X_WA.translation += 0.001 * (std::cos(angle) * e1 + std::sin(angle) * e2);
    q.cycle = cycle++;
    const auto t0 = std::chrono::steady_clock::now();
    const ContactResult r = model.Evaluate(q);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(r);
    max_us = std::max(max_us, us);
    nodes += double(r.stats.nodes_visited);
    contacts += r.stats.points_in_contact;
    level += r.stats.level_rendered;
  }
  const double n = double(std::max<std::int64_t>(1, cycle));
  state.counters["nodes"] = nodes / n;
  state.counters["contacts"] = contacts / n;
  state.counters["level"] = level / n;
  state.counters["max_us"] = max_us;
  state.counters["points"] = points;
  state.counters["ns_per_node"] =
      benchmark::Counter(nodes * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(std::int64_t(nodes));
}

void RegisterAll() {
  struct SceneCase {
    std::string file;
    std::vector<int> points;
  };
  std::vector<SceneCase> scenes;
  if (bench::QuickRun()) {
    scenes = {{"scenes/sphere-on-plate.yaml", {4096}}};
  } else {
    // Sizes 4k..256k points (levels so level 0 keeps ~250 points).
    const std::vector<int> sizes = {4096, 16384, 65536, 262144};
    scenes = {{"scenes/dragon-bunny.yaml", sizes},
              {"scenes/bumpy-cube-plate.yaml", sizes},
              {"scenes/knight-screwdriver.yaml", {4096, 16384, 65536}},
              {"scenes/block-joint.yaml", {4096, 16384, 65536}}};
  }
  for (const SceneCase& sc : scenes) {
    for (int points : sc.points) {
      const int levels = 1 + int(std::round(std::log(points / 256.0) / std::log(4.0)));
      for (int depth = 0; depth < 2; ++depth) {
        for (int v = kLinear; v <= kTreeCoherenceBudget; ++v) {
          const long long budget = 20000;  // nodes per cycle (warm threshold V_W)
          const std::string name = "contact/" + std::filesystem::path(sc.file).stem().string() +
                                   "/points:" + std::to_string(points) + "/" + kVariantNames[v] + "/" +
                                   kDepthNames[depth];
          benchmark::RegisterBenchmark(name.c_str(), BM_ContactCycle, sc.file, points, levels, Variant(v), depth,
                                       budget)
              ->Unit(benchmark::kMicrosecond);
        }
      }
    }
  }
}

}  // namespace
}  // namespace contactlab

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  contactlab::RegisterAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
