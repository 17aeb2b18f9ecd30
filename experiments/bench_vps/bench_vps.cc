// Question: how long does one haptic cycle of the Voxmap-PointShell baseline take (McNeely,
// Puterbaugh & Troy 1999; 8-bit voxmap coherence of 2006) against the paper's tree-less
// pointshell model on the same scene and placement, with the VPS voxel pointshell ("vps"),
// with the paper's repulsion pointshell ("vps-repulsion"), and with temporal coherence?
//
// Each iteration is one cycle: body A slides on a 1 mm circle (6 mm/s) across B's surface at
// the placement depth (found with pointshell-linear). Counters: points (in A's pointshell),
// visited (points looked up per cycle), contacts (points with force), max_us (slowest cycle),
// voxmap_kB and wide_kB (VPS voxmap memory, 2-bit and 8-bit).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contact/register_contact_models.h"
#include "baselines/vps/vps_contact_model.h"
#include "bench_common.h"
#include "bench_main.h"
#include "placed_scene.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "scene/contact_placement.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

using bench::kDepthNames;
using bench::PlacedScene;

void BM_Cycle(benchmark::State& state, std::string scene_file, int points, int levels, std::string model_name,
              bool coherence, int depth) {
  PlacedScene& p = bench::PreparePlacedScene(scene_file, points, levels, /*add_offset=*/false);
  if (!p.ok()) {
    state.SkipWithError("could not place the bodies in contact");
    return;
  }
  Scene scene = p.scene;
  scene.model.coherence = coherence;
  scene.model.max_point_speed = 0.5;  // m/s: bounds the 6 mm/s circle with a wide margin
  std::unique_ptr<ContactModel> model = MakeSceneContactModel(model_name, scene, *p.assets);
  std::int64_t shell_points = 0;
  if (auto* vps = dynamic_cast<VpsContactModel*>(model.get())) {
    const VpsModelInfo info = vps->info();
    state.counters["voxmap_kB"] = double(info.voxmap_bytes) / 1024.0;
    state.counters["wide_kB"] = double(info.wide_voxmap_bytes) / 1024.0;
    state.counters["voxel_mm"] = info.voxel_size * 1e3;
    shell_points = info.points;
  } else {
    shell_points = p.assets->A.pointshell()->num_points();
  }
  const bench::CycleTimes t = bench::TimeCirclingCycles(state, *model, p, depth);
  state.counters["points"] = double(shell_points);
  state.counters["visited"] = t.nodes / double(std::max<std::int64_t>(1, t.cycles));
}

void RegisterAll() {
  RegisterContactModels();
  struct SceneCase {
    std::string file;
    int points, levels;
  };
  std::vector<SceneCase> scenes;
  if (bench::QuickRun()) {
    scenes = {{"scenes/sphere-on-plate.yaml", 1024, 3}};  // small repulsion shell: seconds to build
  } else {
    scenes = {{"scenes/sphere-on-plate.yaml", 8192, 4}};  // the scene as written
    scenes.push_back({"scenes/dragon-bunny.yaml", 16384, 4});  // real meshes, 128^3 fields
  }
  struct ModelCase {
    const char* name;
    bool coherence;
    const char* label;
  };
  const ModelCase models[] = {{"pointshell-linear", false, "pointshell-linear"},
                              {"vps", false, "vps"},
                              {"vps", true, "vps+coherence"},
                              {"vps-repulsion", false, "vps-repulsion"},
                              {"vps-repulsion", true, "vps-repulsion+coherence"}};
  for (const SceneCase& sc : scenes) {
    for (int depth = 0; depth < 2; ++depth) {
      for (const ModelCase& m : models) {
        const std::string name = "vps/" + std::filesystem::path(sc.file).stem().string() + "/points:" +
                                 std::to_string(sc.points) + "/" + m.label + "/" + kDepthNames[depth];
        benchmark::RegisterBenchmark(name.c_str(), BM_Cycle, sc.file, sc.points, sc.levels, std::string(m.name),
                                     m.coherence, depth)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
}

}  // namespace
}  // namespace contactlab

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  contactlab::RegisterAll();
  return contactlab::bench::RunBenchmarks();
}
