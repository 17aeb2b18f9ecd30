// Query points and the timed lookup loop shared by the distance-field benchmarks.
#pragma once

#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "geometry/aabb.h"

namespace contactlab::bench {

// Query points as a structure of arrays (float, as the traversal stores its points).
struct QueryPoints {
  std::vector<float> x, y, z;
  std::size_t size() const { return x.size(); }
  void Add(double px, double py, double pz) {
    x.push_back(float(px));
    y.push_back(float(py));
    z.push_back(float(pz));
  }
};

// N points uniformly random in BOX (fixed seed).
inline QueryPoints RandomPointsInBox(const Aabb& box, int n, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  QueryPoints p;
  for (int s = 0; s < n; ++s) {
    const Eigen::Vector3d t(u(rng), u(rng), u(rng));
    const Eigen::Vector3d q = box.min + t.cwiseProduct(box.max - box.min);
    p.Add(q.x(), q.y(), q.z());
  }
  return p;
}

// The timed loop: LOOKUP(x, y, z) -> distance at every point of P per iteration, summed so no
// lookup is dropped. Sets the items processed and the counter ns_per_lookup (CPU time).
template <class Lookup>
void TimeLookups(benchmark::State& state, const QueryPoints& p, Lookup&& lookup) {
  const std::size_t n = p.size();
  for (auto _ : state) {
    float sum = 0;
    for (std::size_t s = 0; s < n; ++s) sum += lookup(p.x[s], p.y[s], p.z[s]);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(n));
  state.counters["ns_per_lookup"] =
      benchmark::Counter(double(state.iterations()) * double(n) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace contactlab::bench
