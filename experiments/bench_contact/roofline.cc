// The roofline of this machine, so each traversal's ns/point can be read against the bound it
// is closest to: pointer-chase latency (ns per dependent load), stream read-sum and triad
// bandwidth (GB/s), per working set (half of L1d, L2 and L3 as cpu0 reports them, and 4x L3
// for DRAM), and the trilinear DistanceField::Distance lookup at random points in a 128^3 and
// a 256^3 field (cache or DRAM misses) and at random points in an 8-cell cube (cache hits).
#include "roofline.h"

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <fstream>
#include <numeric>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bench_common.h"
#include "field_queries.h"
#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"

namespace contactlab::bench {
namespace {

constexpr std::int64_t kLine = 64;  // bytes per cache line

// Size in bytes of cpu0's data or unified cache of LEVEL (sysfs), or FALLBACK.
std::int64_t CacheBytes(int level, std::int64_t fallback) {
  for (int index = 0; index < 8; ++index) {
    const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index) + "/";
    int l = 0;
    std::string type, size;
    if (!(std::ifstream(dir + "level") >> l) || !(std::ifstream(dir + "type") >> type) ||
        !(std::ifstream(dir + "size") >> size)) {
      continue;
    }
    if (l != level || type == "Instruction" || size.empty()) continue;
    const char unit = size.back();
    const std::int64_t n = std::stoll(size);
    return unit == 'K' ? n << 10 : unit == 'M' ? n << 20 : n;
  }
  return fallback;
}

// Working sets: half of L1d and of L2; for L3 2x L2, at most half of L3 (a VM shares L3 with
// other guests: on the project's machine, which reports 32 MiB, latency is DRAM's from about
// 3 MiB); DRAM at 4x L3, at least 64 MiB. Quick runs: 16 KiB and 256 KiB only.
std::vector<std::pair<std::string, std::int64_t>> WorkingSets() {
  if (QuickRun()) return {{"L1", 16 << 10}, {"L2", 256 << 10}};
  const std::int64_t l2 = CacheBytes(2, 512 << 10), l3 = CacheBytes(3, 8 << 20);
  return {{"L1", CacheBytes(1, 32 << 10) / 2},
          {"L2", l2 / 2},
          {"L3", std::min(2 * l2, l3 / 2)},
          {"DRAM", std::max<std::int64_t>(64 << 20, 4 * l3)}};
}

// One dependent load per hop through a random cyclic permutation of BYTES / 64 cache lines
// (Sattolo's algorithm: a single cycle through every line). Counter ns_per_load.
void BM_PointerChase(benchmark::State& state, std::int64_t bytes) {
  struct alignas(kLine) Line {
    const Line* next;
  };
  const std::int64_t n = bytes / kLine;
  std::vector<Line> lines(n);
  std::vector<std::int64_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(1);
  for (std::int64_t i = n - 1; i > 0; --i) {
    std::swap(order[i], order[std::uniform_int_distribution<std::int64_t>(0, i - 1)(rng)]);
  }
  for (std::int64_t i = 0; i < n; ++i) lines[order[i]].next = &lines[order[(i + 1) % n]];
  const std::int64_t hops = QuickRun() ? 4096 : 1 << 20;
  const Line* p = &lines[0];
  for (auto _ : state) {
    for (std::int64_t h = 0; h < hops; ++h) p = p->next;
    benchmark::DoNotOptimize(p);
  }
  state.counters["ns_per_load"] =
      benchmark::Counter(double(state.iterations()) * hops * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["KiB"] = double(bytes >> 10);
}

// GB/s counter (decimal) for BYTES moved per iteration.
void SetBandwidth(benchmark::State& state, std::int64_t bytes) {
  state.SetBytesProcessed(state.iterations() * bytes);
  state.counters["GB_per_s"] = benchmark::Counter(double(state.iterations()) * double(bytes) * 1e-9,
                                                  benchmark::Counter::kIsRate);
  state.counters["KiB"] = double(bytes >> 10);
}

// Sum of BYTES of 64-bit integers, four independent sums so two loads can issue per cycle
// (integer adds vectorise at the default flags).
void BM_ReadSum(benchmark::State& state, std::int64_t bytes) {
  std::vector<std::uint64_t> v(bytes / 8);
  std::iota(v.begin(), v.end(), 0);
  for (auto _ : state) {
    std::uint64_t s[4] = {0, 0, 0, 0};
    for (std::size_t i = 0; i + 4 <= v.size(); i += 4) {
      for (int k = 0; k < 4; ++k) s[k] += v[i + k];
    }
    benchmark::DoNotOptimize(s);
  }
  SetBandwidth(state, bytes);
}

// STREAM triad a = b + s c on three float arrays of BYTES in total (bytes counted: 2 read, 1
// written; the write-allocate read is not counted, as in STREAM).
void BM_Triad(benchmark::State& state, std::int64_t bytes) {
  const std::size_t n = bytes / (3 * sizeof(float));
  std::vector<float> a(n, 0.f), b(n, 1.f), c(n, 2.f);
  const float s = 0.5f;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  SetBandwidth(state, std::int64_t(3 * n * sizeof(float)));
}

// A sphere's closed field at RESOLUTION cells (129^3 floats: 8.6 MB; 257^3: 68 MB).
const DistanceField& SphereField(int resolution) {
  static std::vector<std::pair<int, DistanceField>> cache;
  for (const auto& [r, f] : cache) {
    if (r == resolution) return f;
  }
  DistanceFieldOptions o;
  o.resolution = resolution;
  o.mode = FieldMode::kClosed;
  o.show_progress = false;
  cache.emplace_back(resolution, BuildDistanceField(MakeSphere(0.1, 5), o));
  return cache.back().second;
}

// Random points in a cube of 8 cells at the field's centre: the samples they read (about 10 KB)
// stay in L1/L2, so this is the lookup's cost from cache.
QueryPoints LocalPoints(const DistanceField& f, int n) {
  const Aabb box = f.box();
  const Eigen::Vector3d c = 0.5 * (box.min + box.max), half = Eigen::Vector3d::Constant(4 * f.spacing());
  Aabb local;
  local.Extend(c - half);
  local.Extend(c + half);
  return RandomPointsInBox(local, n);
}

void BM_TrilinearLookup(benchmark::State& state, int resolution, bool random) {
  const DistanceField& f = SphereField(QuickRun() ? 32 : resolution);
  const int n = QuickRun() ? 1000 : 1 << 20;
  const QueryPoints p = random ? RandomPointsInBox(f.box(), n) : LocalPoints(f, n);
  TimeLookups(state, p, [&f](float x, float y, float z) { return f.Distance(x, y, z); });
  state.counters["field_MB"] = double(f.num_samples()) * sizeof(float) * 1e-6;
}

}  // namespace

void RegisterRooflineBenchmarks() {
  for (const auto& [level, bytes] : WorkingSets()) {
    const std::string suffix = "/" + level + "/KiB:" + std::to_string(bytes >> 10);
    benchmark::RegisterBenchmark(("roofline/latency" + suffix).c_str(), BM_PointerChase, bytes)
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("roofline/read" + suffix).c_str(), BM_ReadSum, bytes)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("roofline/triad" + suffix).c_str(), BM_Triad, bytes)->Unit(benchmark::kMicrosecond);
  }
  for (int resolution : {128, 256}) {  // 8.6 MB (inside L3) and 68 MB (DRAM) of samples
    for (bool random : {true, false}) {
      const std::string name = "roofline/lookup/cells:" + std::to_string(resolution) + (random ? "/random" : "/local");
      benchmark::RegisterBenchmark(name.c_str(), BM_TrilinearLookup, resolution, random)
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

}  // namespace contactlab::bench
