#include "placed_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "scene/contact_placement.h"
#include "util/data_path.h"
#include "util/error.h"

namespace contactlab::bench {

PlacedScene& PreparePlacedScene(const std::string& scene_file, int points, int levels, bool add_offset) {
  static std::map<std::string, PlacedScene> cache;
  const std::string key =
      scene_file + "/" + std::to_string(points) + "/" + std::to_string(levels) + (add_offset ? "/offset" : "");
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  PlacedScene& p = cache[key];
  p.scene = LoadScene(RequireDataFile(scene_file));
  if (points > 0) p.scene.pointshell_body.pointshell.points = points;
  if (levels > 0) p.scene.pointshell_body.pointshell.levels = levels;
  if (const char* field = std::getenv("CONTACTLAB_BENCH_FIELD")) {
    const std::string text = field;
    const auto colon = text.find(':');
    char* end = nullptr;
    const long resolution = colon == std::string::npos ? 0 : std::strtol(text.c_str() + colon + 1, &end, 10);
    const std::string storage = text.substr(0, colon);
    if ((storage != "dense" && storage != "sparse") || resolution < 8 || resolution > kMaxFieldResolution ||
        end == nullptr || *end != 0) {
      std::fprintf(stderr, "CONTACTLAB_BENCH_FIELD: '%s' is not STORAGE:RESOLUTION (dense|sparse, 8..%d)\n", field,
                   kMaxFieldResolution);
      std::exit(2);
    }
    p.scene.field_body.field.storage = storage;
    p.scene.field_body.field.resolution = int(resolution);
  }
  AssetOptions options;
  options.verbose = false;
  p.assets = std::make_unique<SceneAssets>(p.scene, options);
  p.X_WB = p.scene.field_body.pose;
  // Approach from the scene's start pose of A toward B's origin.
  const Pose start = p.scene.pointshell_body.pose;
  if ((p.X_WB.translation - start.translation).norm() > 0) {
    p.direction = (p.X_WB.translation - start.translation).normalized();
  }
  const double extra = add_offset ? p.assets->A.pointshell()->offset : 0.0;
  for (int d = 0; d < 2; ++d) {
    try {
      p.X_WA[d] = TouchAlong(p.scene, *p.assets, /*move_B=*/false, start, p.X_WB, p.direction, kDepths[d] + extra,
                             scene_file);
      p.placed[d] = true;
    } catch (const Error&) {
      p.placed[d] = false;
    }
  }
  return p;
}

CycleTimes TimeCirclingCycles(benchmark::State& state, ContactModel& model, const PlacedScene& p, int depth,
                              std::int64_t node_budget) {
  const Eigen::Vector3d e1 = p.direction.unitOrthogonal(), e2 = p.direction.cross(e1);
  ContactQuery q;
  q.X_WB = p.X_WB;
  q.node_budget = node_budget;
  CycleTimes out;
  std::vector<double> cycle_us;
  cycle_us.reserve(1 << 20);
  for (auto _ : state) {
    const double angle = 2 * M_PI * double(out.cycles) / 1000.0;  // one turn per second
    q.X_WA = p.X_WA[depth];
    q.X_WA.translation += 0.001 * (std::cos(angle) * e1 + std::sin(angle) * e2);
    q.cycle = out.cycles++;
    const auto t0 = std::chrono::steady_clock::now();
    const ContactResult r = model.Evaluate(q);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(r);
    out.max_us = std::max(out.max_us, us);
    if (cycle_us.size() < cycle_us.capacity()) cycle_us.push_back(us);
    out.nodes += double(r.stats.nodes_visited);
    out.contacts += r.stats.points_in_contact;
    out.level += r.stats.level_rendered;
  }
  const double n = double(std::max<std::int64_t>(1, out.cycles));
  state.counters["contacts"] = out.contacts / n;
  state.counters["max_us"] = out.max_us;
  if (!cycle_us.empty()) {
    std::sort(cycle_us.begin(), cycle_us.end());
    state.counters["p99_us"] = cycle_us[std::size_t(0.99 * double(cycle_us.size() - 1))];
    state.counters["p999_us"] = cycle_us[std::size_t(0.999 * double(cycle_us.size() - 1))];
  }
  state.SetItemsProcessed(std::int64_t(out.nodes));
  return out;
}

}  // namespace contactlab::bench
