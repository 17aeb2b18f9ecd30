// How does our dense field (Barbič & James 2008, sec. 2.3) compare with OpenVDB's narrow-band
// meshToSignedDistanceField on the dragon, and what would a sparse field cost per lookup?
//  * vdb_build/cells:N: OpenVDB's build (band ±3 voxels) at the dense 256^3 field's spacing
//    and at 1024 cells along the same padded box's longest side; wall time (the build is
//    parallel, as ours: compare with bench_sdf_build's BM_BuildClosedField/256). Counters: MB
//    (grid->memUsage()), dense_MB (a dense field at the same spacing), active voxels, and the
//    dense 256^3 interpolant against OpenVDB at its active voxels: max_diff / rms_diff (in
//    OpenVDB voxels; at 1024 mostly the dense field's coarser resolution) and sign
//    disagreements where |d| >= 1 voxel.
//  * lookup/cells:N/METHOD/ORDER: ns per lookup at points in OpenVDB's band at N (active voxel
//    centres jittered by up to half a voxel), in leaf order (coherent) or shuffled (random);
//    METHOD dense (DistanceField::Distance on the 256^3 field), vdb_sampler
//    (GridSampler<FloatGrid, BoxSampler>::wsSample), vdb_accessor (BoxSampler through a
//    cached ConstAccessor, world-to-index inline as the dense lookup does it), sparse (our
//    narrow-band field at N, sdf/sparse_field.h, DistanceField::Distance), and dense_batch /
//    sparse_batch (the vectorised BatchDistances the contact models call, 256 points a call).
//    With CONTACTLAB_BENCH_DENSE_1024=1 also dense_same / dense_same_batch: a dense field at N
//    cells itself (the dragon at 1024: 1.9 GB, 5.8 GB while it is built, minutes), the lookup cost a
//    dense field of the sparse one's resolution would have.
//  * sparse_build/cells:N: our narrow-band field (band ±3 voxels) at N cells, wall time.
//    Counters: MB (memory_bytes), stored bricks, OpenVDB's field on the very same grid points
//    against ours (max_diff / rms_diff in voxels, sign disagreements where |d| >= 1 voxel), and
//    ours against exact distances (BVH + pseudo-normals) at up to 2^17 of OpenVDB's active
//    voxels: exact_max_diff / exact_rms_diff (voxels) and vdb_exact_max_diff for OpenVDB;
//    band_max_diff: ours against OpenVDB at those voxels within the band (|exact| <= 3 voxels).
//    Beyond the band the two differ by design: ours holds bounds there (sparse_field.h).
// Quick mode (CONTACTLAB_BENCH_QUICK=1): a small sphere, 32 and 128 cells.
#include <benchmark/benchmark.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>

#include "baselines/reference/openvdb_field.h"
#include "bench_common.h"
#include "bench_main.h"
#include "bench_mesh.h"
#include "field_queries.h"
#include "sdf/batch_distance.h"
#include "sdf/build_distance_field.h"
#include "sdf/field_grid.h"
#include "sdf/mesh_signed_distance.h"
#include "sdf/signed_distance_grid.h"
#include "sdf/sparse_field.h"

namespace contactlab {
namespace {

constexpr int kDenseCells = 256;

// Quick runs use 1/8 of every resolution.
int Cells(int cells) { return bench::QuickRun() ? cells / 8 : cells; }

const DistanceField& DenseField() {
  static const DistanceField field = [] {
    DistanceFieldOptions o;
    o.resolution = Cells(kDenseCells);
    o.mode = FieldMode::kClosed;
    o.show_progress = false;
    return BuildDistanceField(bench::BenchMesh(), o);
  }();
  return field;
}

// OpenVDB's field on the dense field's grid points refined to CELLS along the longest side.
openvdb::FloatGrid::Ptr BuildVdb(int cells) {
  const DistanceField& dense = DenseField();
  return BuildOpenVdbField(bench::BenchMesh(), dense.origin(), dense.spacing() * Cells(kDenseCells) / cells);
}

const openvdb::FloatGrid& CachedVdb(int cells) {
  static std::vector<std::pair<int, openvdb::FloatGrid::Ptr>> cache;
  for (const auto& [c, g] : cache) {
    if (c == cells) return *g;
  }
  cache.emplace_back(cells, BuildVdb(cells));
  return *cache.back().second;
}

// Sparse fields need at least 64 cells (quick runs ask for 32).
DistanceField BuildSparse(int cells) {
  DistanceFieldOptions o;
  o.resolution = std::max(64, cells);
  o.mode = FieldMode::kClosed;
  o.storage = FieldStorage::kSparse;
  o.show_progress = false;
  return BuildDistanceField(bench::BenchMesh(), o);
}

const DistanceField& CachedSparse(int cells) {
  static std::vector<std::pair<int, DistanceField>> cache;
  for (const auto& [c, f] : cache) {
    if (c == cells) return f;
  }
  cache.emplace_back(cells, BuildSparse(cells));
  return cache.back().second;
}

void BM_SparseBuild(benchmark::State& state, int cells) {
  cells = Cells(cells);
  DistanceField field;
  for (auto _ : state) {
    field = BuildSparse(cells);
    benchmark::DoNotOptimize(&field);
  }
  // OpenVDB on our fine grid's points, so both are compared at their own samples.
  const openvdb::FloatGrid::Ptr vdb = BuildOpenVdbField(bench::BenchMesh(), field.origin(), field.spacing());
  const FieldDifference d = CompareWithOpenVdb(field, *vdb);
  // Both against exact distances at up to 2^17 of OpenVDB's active voxels.
  const MeshSignedDistance exact(bench::BenchMesh(), "bench mesh");
  const std::int64_t stride = std::max<std::int64_t>(1, std::int64_t(vdb->activeVoxelCount()) >> 17);
  const double h = field.spacing();
  double ours_max = 0, ours2 = 0, vdb_max = 0, band_diff = 0;
  std::int64_t n = 0, i = 0;
  for (auto it = vdb->cbeginValueOn(); it; ++it, ++i) {
    if (i % stride != 0) continue;
    const openvdb::Vec3d p = vdb->indexToWorld(it.getCoord());
    const Eigen::Vector3d q(p.x(), p.y(), p.z());
    if (!field.Inside(q)) continue;
    const double e = exact.Distance(q);
    const double ours = std::abs(field.Distance(q) - e) / h;
    ours_max = std::max(ours_max, ours);
    ours2 += ours * ours;
    vdb_max = std::max(vdb_max, std::abs(double(*it) - e) / h);
    if (std::abs(e) <= field.sparse()->band_voxels * h) band_diff = std::max(band_diff, std::abs(field.Distance(q) - *it) / h);
    ++n;
  }
  state.counters["MB"] = double(field.memory_bytes()) * 1e-6;
  state.counters["vdb_MB"] = double(vdb->memUsage()) * 1e-6;
  state.counters["bricks"] = double(field.sparse()->num_stored());
  state.counters["max_diff"] = d.max_voxels;
  state.counters["rms_diff"] = d.rms_voxels;
  state.counters["sign_errors"] = double(d.sign_disagreements);
  state.counters["exact_max_diff"] = ours_max;
  state.counters["exact_rms_diff"] = n > 0 ? std::sqrt(ours2 / double(n)) : 0;
  state.counters["vdb_exact_max_diff"] = vdb_max;
  state.counters["band_max_diff"] = band_diff;  // ours against OpenVDB where |exact| <= band
}

void BM_VdbBuild(benchmark::State& state, int cells) {
  cells = Cells(cells);
  const DistanceField& dense = DenseField();
  openvdb::FloatGrid::Ptr grid;
  for (auto _ : state) {
    grid = BuildVdb(cells);
    benchmark::DoNotOptimize(grid.get());
  }
  const FieldDifference d = CompareWithOpenVdb(dense, *grid);
  const FieldGrid same_spacing = MakeFieldGrid(bench::BenchMesh().Bounds(), cells, DistanceFieldOptions().padding);
  state.counters["MB"] = double(grid->memUsage()) * 1e-6;
  state.counters["dense_MB"] = double(same_spacing.num_points()) * sizeof(float) * 1e-6;
  state.counters["active"] = double(grid->activeVoxelCount());
  state.counters["max_diff"] = d.max_voxels;
  state.counters["rms_diff"] = d.rms_voxels;
  state.counters["sign_errors"] = double(d.sign_disagreements);
}

// Up to 2^20 points in GRID's band: active voxel centres (every k-th, leaf order) jittered by
// up to half a voxel; shuffled when RANDOM.
bench::QueryPoints BandPoints(const openvdb::FloatGrid& grid, bool random) {
  const std::int64_t n = bench::QuickRun() ? 1000 : 1 << 20;
  const std::int64_t stride = std::max<std::int64_t>(1, std::int64_t(grid.activeVoxelCount()) / n);
  const double h = grid.voxelSize()[0];
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> jitter(-0.5 * h, 0.5 * h);
  std::vector<openvdb::Vec3d> p;
  std::int64_t i = 0;
  for (auto it = grid.cbeginValueOn(); it; ++it, ++i) {
    if (i % stride == 0) p.push_back(grid.indexToWorld(it.getCoord()) + openvdb::Vec3d(jitter(rng), jitter(rng), jitter(rng)));
  }
  if (random) std::shuffle(p.begin(), p.end(), rng);
  bench::QueryPoints q;
  for (const openvdb::Vec3d& x : p) q.Add(x.x(), x.y(), x.z());
  return q;
}

enum Method { kDense, kVdbSampler, kVdbAccessor, kSparse, kDenseBatch, kSparseBatch, kDenseSame, kDenseSameBatch };
const char* kMethodNames[] = {"dense",        "vdb_sampler", "vdb_accessor", "sparse",
                              "dense_batch",  "sparse_batch", "dense_same",  "dense_same_batch"};

bool DenseSameResolution() {
  const char* v = std::getenv("CONTACTLAB_BENCH_DENSE_1024");
  return v != nullptr && std::string(v) == "1";
}

// The dense field on the sparse field's own fine grid (same points, same resolution).
const DistanceField& CachedDenseSame(int cells) {
  static std::vector<std::pair<int, DistanceField>> cache;
  for (const auto& [c, f] : cache) {
    if (c == cells) return f;
  }
  const DistanceField& sparse = CachedSparse(cells);
  FieldGrid grid;
  grid.origin = sparse.origin();
  grid.spacing = sparse.spacing();
  grid.dims = sparse.dims();
  cache.emplace_back(cells, DistanceField(grid.origin, grid.spacing, grid.dims,
                                          ComputeSignedDistance(bench::BenchMesh(), grid, 3)));
  return cache.back().second;
}

// BatchDistances over P in calls of 256 points (the chunk the linear traversal uses is 512;
// a tree level is often smaller), identity pose. Same counters as TimeLookups.
void TimeBatchLookups(benchmark::State& state, const bench::QueryPoints& p, const DistanceField& f) {
  constexpr int kChunk = 256;
  const int n = int(p.size());
  float d[kChunk];
  for (auto _ : state) {
    float sum = 0;
    for (int s = 0; s < n; s += kChunk) {
      const int m = std::min(kChunk, n - s);
      BatchDistances(f, kIdentityTransform, p.x.data() + s, p.y.data() + s, p.z.data() + s, nullptr, m, d);
      for (int k = 0; k < m; ++k) sum += d[k];
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t(n));
  state.counters["ns_per_lookup"] = benchmark::Counter(double(state.iterations()) * double(n) * 1e-9,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Lookup(benchmark::State& state, int cells, Method method, bool random) {
  const openvdb::FloatGrid& grid = CachedVdb(Cells(cells));
  const bench::QueryPoints p = BandPoints(grid, random);
  if (method == kSparse || method == kSparseBatch || method == kDenseBatch || method == kDenseSame ||
      method == kDenseSameBatch) {
    const DistanceField& f = method == kDenseBatch                                   ? DenseField()
                             : (method == kDenseSame || method == kDenseSameBatch) ? CachedDenseSame(Cells(cells))
                                                                                     : CachedSparse(Cells(cells));
    if (const SparseFieldStorage* sp = f.sparse()) {
      // The share of points outside stored bricks (the coarse path), and of 16-point vectors
      // with at least one such point.
      std::int64_t coarse = 0, mixed = 0;
      for (std::size_t k = 0; k < p.size(); k += 16) {
        bool any = false;
        for (std::size_t j = k; j < std::min(p.size(), k + 16); ++j) {
          const Eigen::Vector3d g = (Eigen::Vector3d(p.x[j], p.y[j], p.z[j]) - f.origin()) / f.spacing();
          const Eigen::Vector3i c = g.cast<int>().cwiseMax(0).cwiseMin(f.dims() - Eigen::Vector3i::Constant(2));
          const bool stored = sp->slot[sp->BrickIndex(c.x() / 8, c.y() / 8, c.z() / 8)] >= 0;
          coarse += !stored;
          any = any || !stored;
        }
        mixed += any;
      }
      state.counters["unstored"] = double(coarse) / double(p.size());
      state.counters["vectors_unstored"] = double(mixed) / double((p.size() + 15) / 16);
    }
    if (method == kSparse || method == kDenseSame) {
      bench::TimeLookups(state, p, [&f](float x, float y, float z) { return f.Distance(x, y, z); });
    } else {
      TimeBatchLookups(state, p, f);
    }
  } else if (method == kDense) {
    const DistanceField& f = DenseField();
    bench::TimeLookups(state, p, [&f](float x, float y, float z) { return f.Distance(x, y, z); });
  } else if (method == kVdbSampler) {
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(grid);
    bench::TimeLookups(state, p, [&sampler](float x, float y, float z) {
      return sampler.wsSample(openvdb::Vec3d(x, y, z));
    });
  } else {
    const openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const openvdb::Vec3d o = grid.indexToWorld(openvdb::Vec3d(0, 0, 0));
    const double inv_h = 1 / grid.voxelSize()[0];
    bench::TimeLookups(state, p, [&accessor, o, inv_h](float x, float y, float z) {
      const openvdb::Vec3d ijk((x - o.x()) * inv_h, (y - o.y()) * inv_h, (z - o.z()) * inv_h);
      return openvdb::tools::BoxSampler::sample(accessor, ijk);
    });
  }
}

void RegisterAll() {
  for (int cells : {256, 1024}) {  // the dense field's spacing, and 4x finer
    benchmark::RegisterBenchmark(("vdb_build/cells:" + std::to_string(cells)).c_str(), BM_VdbBuild, cells)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(bench::QuickRun() ? 1 : 3);
    benchmark::RegisterBenchmark(("sparse_build/cells:" + std::to_string(cells)).c_str(), BM_SparseBuild, cells)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(bench::QuickRun() ? 1 : 3);
  }
  for (int cells : {256, 1024}) {
    for (int m = kDense; m <= (DenseSameResolution() ? kDenseSameBatch : kSparseBatch); ++m) {
      for (bool random : {false, true}) {
        const std::string name = "lookup/cells:" + std::to_string(cells) + "/" + kMethodNames[m] +
                                 (random ? "/random" : "/coherent");
        benchmark::RegisterBenchmark(name.c_str(), BM_Lookup, cells, Method(m), random)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
}
[[maybe_unused]] const bool kRegistered = (RegisterAll(), true);  // before main() runs

}  // namespace
}  // namespace contactlab

CONTACTLAB_BENCHMARK_MAIN()
