// How long does building a distance field take (Barbič & James 2008, sec. 2.3)? Closed
// pipeline on dragon.obj at 128^3 and 256^3 (target: 256^3 in <= 20 s on 2 cores); in quick
// mode (CONTACTLAB_BENCH_QUICK=1) a small procedural sphere at 32^3.
#include <benchmark/benchmark.h>

#include "bench_common.h"
#include "bench_main.h"
#include "bench_mesh.h"
#include "sdf/build_distance_field.h"

namespace contactlab {
namespace {

void BM_BuildClosedField(benchmark::State& state) {
  const TriangleMesh& mesh = bench::BenchMesh();
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
  state.counters["MB"] = double(samples) * sizeof(float) * 1e-6;
}
BENCHMARK(BM_BuildClosedField)
    ->Arg(128)  // dragon at 128 cells along the longest side
    ->Arg(256)  // dragon at 256 cells: the target case
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_BuildSoupField(benchmark::State& state) {
  TriangleMesh mesh = bench::BenchMesh();
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

CONTACTLAB_BENCHMARK_MAIN()
