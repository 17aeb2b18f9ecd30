// How long does building a distance field take (Barbič & James 2008, sec. 2.3)? Closed
// pipeline on dragon.obj at 128^3 and 256^3 (target: 256^3 in <= 20 s on 2 cores); in quick
// mode (CONTACTLAB_BENCH_QUICK=1) a small procedural sphere at 32^3.
#include <benchmark/benchmark.h>

#include <iostream>

#include "bench_common.h"
#include "geometry/mesh_io.h"
#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

const TriangleMesh& BenchMesh() {
  static const TriangleMesh mesh = [] {
    if (bench::QuickRun()) return MakeSphere(0.1, 3);
    const auto path = FindDataFile("dragon.obj");
    if (!path) {
      std::cerr << "dragon.obj not found on the data search path; using a procedural sphere\n";
      return MakeSphere(0.1, 7);
    }
    return LoadMesh(*path);
  }();
  return mesh;
}

void BM_BuildClosedField(benchmark::State& state) {
  const TriangleMesh& mesh = BenchMesh();
  DistanceFieldOptions options;
  options.resolution = bench::QuickRun() ? 32 : int(state.range(0));
  options.mode = FieldMode::kClosed;
  options.show_progress = false;
  std::int64_t samples = 0;
  for (auto _ : state) {
    DistanceField f = BuildDistanceField(mesh, options);
    samples = f.num_samples();
    benchmark::DoNotOptimize(f.values().data());
  }
  state.SetItemsProcessed(state.iterations() * samples);
  state.counters["triangles"] = mesh.num_triangles();
}
BENCHMARK(BM_BuildClosedField)
    ->Arg(128)  // dragon at 128 cells along the longest side
    ->Arg(256)  // dragon at 256 cells: the target case
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_BuildSoupField(benchmark::State& state) {
  TriangleMesh mesh = BenchMesh();
  mesh.triangles.pop_back();  // an open surface: the soup pipeline
  DistanceFieldOptions options;
  options.resolution = bench::QuickRun() ? 32 : int(state.range(0));
  options.mode = FieldMode::kSoup;
  options.show_progress = false;
  std::int64_t samples = 0;
  for (auto _ : state) {
    DistanceField f = BuildDistanceField(mesh, options);
    samples = f.num_samples();
    benchmark::DoNotOptimize(f.values().data());
  }
  state.SetItemsProcessed(state.iterations() * samples);
}
BENCHMARK(BM_BuildSoupField)
    ->Arg(128)  // dragon minus one triangle, soup pipeline at 128 cells
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace contactlab

BENCHMARK_MAIN();
