// How long does building the paper's pointshell take? A 256,000-point, 5-level repulsion
// pointshell of dragon.obj on a 128^3 field (Barbič & James 2008, sec. 2.4: "1 to 2 hours";
// our target: <= 60 s on 2 cores), with the quality report of the result. Quick mode
// (CONTACTLAB_BENCH_QUICK=1): 4,096 points, 4 levels on an analytic sphere field.
#include <benchmark/benchmark.h>

#include <cmath>
#include <iostream>
#include <optional>

#include "bench_common.h"
#include "bench_main.h"
#include "geometry/mesh_io.h"
#include "pointshell/build_pointshell.h"
#include "pointshell/pointshell_quality.h"
#include "sdf/build_distance_field.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

// Exact distance of a sphere of radius 0.3 sampled on 65^3 points over [-0.5, 0.5]^3.
DistanceField SphereField() {
  const int n = 65;
  const double h = 1.0 / (n - 1);
  std::vector<float> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(float((Eigen::Vector3d(i, j, k) * h - Eigen::Vector3d::Constant(0.5)).norm() - 0.3));
  return DistanceField(Eigen::Vector3d::Constant(-0.5), h, Eigen::Vector3i::Constant(n), std::move(v),
                       {"sphere", "analytic", 0, 0});
}

// The field of the benchmark: dragon.obj at resolution 128 (the field build is not timed).
const DistanceField& Field() {
  static const DistanceField field = [] {
    if (bench::QuickRun()) return SphereField();
    MeshLoadOptions load;
    TriangleMesh mesh = LoadMesh(RequireDataFile("dragon.obj"), load);
    mesh.name = "dragon.obj";
    DistanceFieldOptions options;
    options.resolution = 128;
    options.show_progress = false;
    return BuildDistanceField(mesh, options);
  }();
  return field;
}

void BM_BuildRepulsionPointshell(benchmark::State& state) {
  const DistanceField& field = Field();
  PointshellOptions options;
  options.num_points = bench::QuickRun() ? 4096 : std::int32_t(state.range(0));
  options.num_levels = bench::QuickRun() ? 4 : int(state.range(1));
  options.seed = 1;
  options.show_progress = false;
  std::optional<Pointshell> shell;
  PointshellBuildReport report;
  for (auto _ : state) {
    shell = BuildPointshell(field, options, nullptr, &report);
    benchmark::DoNotOptimize(shell->x.data());
  }
  state.SetItemsProcessed(state.iterations() * options.num_points);
  state.counters["points"] = options.num_points;
  state.counters["build_s"] = report.seconds;
  // Quality of the last build (not timed).
  const PointshellQuality q = AssessPointshell(*shell, &field);
  state.counters["cv_deepest"] = q.levels.back().spacing_cv;
  state.counters["cover_over_spacing"] = q.levels.back().covering_radius / q.levels.back().spacing_mean;
  std::cerr << QualityToText(q);
  for (std::size_t i = 0; i < report.levels.size(); ++i) {
    const auto& l = report.levels[i];
    std::cerr << "  repulsion level " << i << ": " << l.free_points << " new, " << l.iterations << " iterations"
              << (l.converged ? " (converged), " : " (limit), ") << l.seconds << " s\n";
  }
}
BENCHMARK(BM_BuildRepulsionPointshell)
    ->Args({256000, 5})  // the paper's size: 256,000 points in 5 levels (1,000 at level 0)
    ->Args({64000, 4})   // a quarter: 64,000 points in 4 levels
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace contactlab

CONTACTLAB_BENCHMARK_MAIN()
