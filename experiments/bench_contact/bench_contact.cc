// Question: how long does one haptic cycle of the paper's contact model take, against
// pointshell size, for the tree-less (linear) traversal, the tree, the tree with temporal
// coherence, and the tree with coherence under a node budget (graceful degradation), on real
// mesh pairs in shallow and in deep contact? (Barbič & James 2008, sec. 3 and Table 1.)
//
// Each iteration is one cycle: body A slides on a 1 mm circle (6 mm/s) across B's surface
// while held at the placement depth, so coherence sees a moving configuration. Counters:
// ns_per_node, nodes (visited per cycle), contacts, level, p99_us / p999_us / max_us (cycle
// time percentiles and the slowest cycle, which includes the operating system's jitter).
// CONTACTLAB_BENCH_LARGE_POINTS=1048576,4194304 replaces the scenes with dragon-bunny at those sizes.
// Beside them, roofline/*: the machine's memory latency and bandwidth per cache level and the
// cost of one trilinear field lookup (roofline.h), the bounds a traversal's ns/point is read
// against.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_common.h"
#include "bench_main.h"
#include "placed_scene.h"
#include "roofline.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "scene/contact_placement.h"
#include "scene/scene_assets.h"
#include "scene/scene.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

using bench::kDepthNames;
using bench::PlacedScene;

enum Variant { kLinear, kTree, kTreeCoherence, kTreeCoherenceBudget };
const char* kVariantNames[] = {"linear", "tree", "tree+coherence", "tree+coherence+budget"};

void BM_ContactCycle(benchmark::State& state, std::string scene_file, int points, int levels, Variant variant,
                     int depth, long long budget) {
  PlacedScene& p = bench::PreparePlacedScene(scene_file, points, levels, /*add_offset=*/false);
  if (!p.ok()) {
    state.SkipWithError("could not place the bodies in contact");
    return;
  }
  PointshellContactParams params = PaperModelParams(p.scene);
  params.coherence = variant >= kTreeCoherence;
  params.max_point_speed = 0.5;
  PointshellContactModel model(variant == kLinear ? PointshellContactModel::Variant::kLinear
                                                  : PointshellContactModel::Variant::kTree,
                               p.assets->A.pointshell(), p.assets->B.field(), params);
  const bench::CycleTimes t =
      bench::TimeCirclingCycles(state, model, p, depth, variant == kTreeCoherenceBudget ? budget : 0);
  const double n = double(std::max<std::int64_t>(1, t.cycles));
  state.counters["nodes"] = t.nodes / n;
  state.counters["level"] = t.level / n;
  state.counters["points"] = points;
  state.counters["ns_per_node"] =
      benchmark::Counter(t.nodes * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void RegisterAll() {
  struct SceneCase {
    std::string file;
    std::vector<int> points;
  };
  std::vector<SceneCase> scenes;
  if (bench::QuickRun()) {
    scenes = {{"scenes/sphere-on-plate.yaml", {4096}}};
  } else if (const char* large = std::getenv("CONTACTLAB_BENCH_LARGE_POINTS")) {
    // Scale study beyond the default sizes (a 1M-point pointshell takes minutes to build the
    // first time, then comes from the cache): dragon-bunny at the comma-separated sizes.
    std::vector<int> sizes;
    for (const char* c = large;;) {
      char* end = nullptr;
      const long n = std::strtol(c, &end, 10);
      if (end == c || n < 256 || n > (1L << 26) || (*end != ',' && *end != 0)) {
        std::fprintf(stderr, "CONTACTLAB_BENCH_LARGE_POINTS: '%s' is not a list of sizes 256..2^26\n", large);
        std::exit(2);
      }
      sizes.push_back(int(n));
      if (*end == 0) break;
      c = end + 1;
    }
    scenes = {{"scenes/dragon-bunny.yaml", sizes}};
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
  contactlab::bench::RegisterRooflineBenchmarks();
  return contactlab::bench::RunBenchmarks();
}
