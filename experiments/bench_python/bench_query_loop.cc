// Question: what does a batch of contact queries cost when looped in C++, the baseline of the
// Python module's Model.query_many (python/model_bindings.cc), which runs the same loop
// (Reset, then Evaluate, per pose) with the GIL released? bench_query_many.py times the Python
// side on the same poses (PathPoses below, repeated there).
//
// Scene: data/scenes/sphere-on-plate.yaml; ->Args: {model index, batch size}.
// Quick mode (CONTACTLAB_BENCH_QUICK=1): batches of 100.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "contact/register_contact_models.h"
#include "bench_common.h"
#include "bench_main.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene/scene_query.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

const char* const kModels[] = {"pointshell", "pointshell-linear", "vps"};

// N poses of A circling 5 mm around its scene pose, 7 turns, sinking from 0.5 mm above it to
// 2.5 mm below: contact of changing depth. bench_query_many.py computes the same poses.
std::vector<Pose> PathPoses(const Pose& X_WA, int n) {
  std::vector<Pose> poses(std::size_t(n), X_WA);
  for (int i = 0; i < n; ++i) {
    const double t = n > 1 ? double(i) / (n - 1) : 0.0;
    const double angle = 7.0 * 2.0 * std::numbers::pi * t;
    poses[std::size_t(i)].translation += Eigen::Vector3d(0.005 * std::cos(angle), 0.005 * std::sin(angle), 0.0005 - 0.003 * t);
  }
  return poses;
}

void BM_QueryLoop(benchmark::State& state) {
  RegisterContactModels();
  const std::string model_name = kModels[state.range(0)];
  const int n = bench::QuickRun() ? 100 : int(state.range(1));
  const Scene scene = LoadScene(RequireDataFile("scenes/sphere-on-plate.yaml"));
  AssetOptions options;
  options.verbose = false;
  SceneAssets assets(scene, options);
  std::unique_ptr<ContactModel> model = MakeSceneContactModel(model_name, scene, assets);
  const std::vector<Pose> poses_A = PathPoses(scene.pointshell_body.pose, n);
  std::vector<double> wrenches(6 * std::size_t(n));
  for (auto _ : state) {
    for (int i = 0; i < n; ++i) {
      const ContactQuery q = SceneContactQuery(scene, poses_A[std::size_t(i)], scene.field_body.pose);
      model->Reset();
      const ContactResult r = model->Evaluate(q);
      Eigen::Map<Vector6d>(wrenches.data() + 6 * i) = r.on_B.AsVector();
    }
    benchmark::DoNotOptimize(wrenches.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.SetLabel(model_name);
}
BENCHMARK(BM_QueryLoop)
    ->Args({0, 10000})  // pointshell (tree), 10,000 poses
    ->Args({1, 10000})  // pointshell-linear, 10,000 poses
    ->Args({2, 10000})  // vps, 10,000 poses
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace contactlab

CONTACTLAB_BENCHMARK_MAIN()
