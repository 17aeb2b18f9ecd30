// A benchmark program for the test of bench_main.h: BM_Completes runs, BM_ReportsAnError calls
// SkipWithError as a benchmark whose model refuses its scene does. Its program must exit 1
// when BM_ReportsAnError runs (bench_smoke.AnErroringBenchmarkFailsItsProgram) and 0 when only
// BM_Completes does.
#include <benchmark/benchmark.h>

#include "bench_main.h"

namespace {

void BM_Completes(benchmark::State& state) {
  int x = 0;
  for (auto _ : state) benchmark::DoNotOptimize(++x);
}
BENCHMARK(BM_Completes);

void BM_ReportsAnError(benchmark::State& state) {
  state.SkipWithError("the model refused the scene");
  for (auto _ : state) {
  }
}
BENCHMARK(BM_ReportsAnError);

}  // namespace

CONTACTLAB_BENCHMARK_MAIN()
