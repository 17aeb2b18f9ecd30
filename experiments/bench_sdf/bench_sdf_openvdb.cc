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
//    (GridSampler<FloatGrid, BoxSampler>::wsSample) or vdb_accessor (BoxSampler through a
//    cached ConstAccessor, world-to-index inline as the dense lookup does it).
// Quick mode (CONTACTLAB_BENCH_QUICK=1): a small sphere, 32 and 128 cells.
#include <benchmark/benchmark.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <random>
#include <string>

#include "baselines/reference/openvdb_field.h"
#include "bench_common.h"
#include "bench_mesh.h"
#include "field_queries.h"
#include "sdf/build_distance_field.h"
#include "sdf/field_grid.h"

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

enum Method { kDense, kVdbSampler, kVdbAccessor };
const char* kMethodNames[] = {"dense", "vdb_sampler", "vdb_accessor"};

void BM_Lookup(benchmark::State& state, int cells, Method method, bool random) {
  const openvdb::FloatGrid& grid = CachedVdb(Cells(cells));
  const bench::QueryPoints p = BandPoints(grid, random);
  if (method == kDense) {
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
  }
  for (int cells : {256, 1024}) {
    for (int m = kDense; m <= kVdbAccessor; ++m) {
      for (bool random : {false, true}) {
        const std::string name = "lookup/cells:" + std::to_string(cells) + "/" + kMethodNames[m] +
                                 (random ? "/random" : "/coherent");
        benchmark::RegisterBenchmark(name.c_str(), BM_Lookup, cells, Method(m), random)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
}
[[maybe_unused]] const bool kRegistered = (RegisterAll(), true);  // before BENCHMARK_MAIN's main() runs

}  // namespace
}  // namespace contactlab

BENCHMARK_MAIN();
