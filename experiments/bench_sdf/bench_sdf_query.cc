// How fast are trilinear distance queries (Barbič & James 2008, sec. 2.3)? Coherent points (a
// spiral over a sphere's offset surface, consecutive points close together, as a pointshell
// traversal visits them) against random points in the field box; target >= 50 M coherent
// queries/s per core. Quick mode (CONTACTLAB_BENCH_QUICK=1): a 32^3 field, few points.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "bench_common.h"
#include "bench_main.h"
#include "field_queries.h"
#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"

namespace contactlab {
namespace {

const DistanceField& Field() {
  static const DistanceField field = [] {
    DistanceFieldOptions o;
    o.resolution = bench::QuickRun() ? 32 : 256;
    o.mode = FieldMode::kClosed;
    o.show_progress = false;
    return BuildDistanceField(MakeSphere(0.1, 5), o);
  }();
  return field;
}

using bench::QueryPoints;

QueryPoints CoherentPoints(int n) {
  // Fibonacci spiral on the sphere of radius 0.101, ordered by polar angle.
  QueryPoints p;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int s = 0; s < n; ++s) {
    const double zc = 1 - 2 * (s + 0.5) / n, r = std::sqrt(1 - zc * zc), phi = golden * s;
    p.Add(0.101 * r * std::cos(phi), 0.101 * r * std::sin(phi), 0.101 * zc);
  }
  return p;
}

void RunQueries(benchmark::State& state, const QueryPoints& p) {
  const DistanceField& f = Field();
  bench::TimeLookups(state, p, [&f](float x, float y, float z) { return f.Distance(x, y, z); });
}

void BM_CoherentQueries(benchmark::State& state) {
  RunQueries(state, CoherentPoints(bench::QuickRun() ? 1000 : int(state.range(0))));
}
BENCHMARK(BM_CoherentQueries)
    ->Arg(10000)    // a pointshell-sized batch along a surface
    ->Arg(1000000)  // a large batch: the field's cache footprint matters more
    ->Unit(benchmark::kMicrosecond);

void BM_RandomQueries(benchmark::State& state) {
  RunQueries(state, bench::RandomPointsInBox(Field().box(), bench::QuickRun() ? 1000 : int(state.range(0))));
}
BENCHMARK(BM_RandomQueries)
    ->Arg(10000)    // random points in the box, cache misses dominate
    ->Arg(1000000)  // same, large batch
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace contactlab

CONTACTLAB_BENCHMARK_MAIN()
