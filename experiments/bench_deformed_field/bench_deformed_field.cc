// How fast is the deformed distance field (Barbič & James 2008, sec. 4.2; issue target: one
// query <= 150 ns at r = 15, k = 5, 40 proxies), what does its per-cycle update cost, and should
// the k nearest deformed proxies be found by a brute-force scan or by a k-d tree (nanoflann),
// which must be rebuilt every cycle because the proxies move?
//
// The body: the armadillo, 20 cm tall, field resolution 80, linear modal model (r = 15, 16
// cells, upper body anchored), legs pulled apart until the feet have moved 2 cm (10% of its
// height), as in experiments/fig10-deformed-field.yaml. Query points: 4096 points of the contact
// band |d| <= 2 cells of the deformed surface, in random order.
// Quick mode (CONTACTLAB_BENCH_QUICK=1): a procedural bar, field 32, 8 cells, r = 6.
#include <benchmark/benchmark.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <tuple>

#include "bench_common.h"
#include "bench_main.h"
#include "deform/deformed_field_accuracy.h"
#include "deform/deformed_field_batch.h"
#include "deform/reduced_model.h"
#include "geometry/mesh_io.h"
#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "util/data_path.h"
#include "util/error.h"

namespace contactlab {
namespace {

struct Setup {
  std::shared_ptr<const DistanceField> field;
  ReducedModel model;
  Eigen::VectorXd q;
  std::vector<float> points;  // 4096 band points, 3 floats each
};

const Setup& GetSetup() {
  static const Setup setup = [] {
    Setup s;
    TriangleMesh mesh;
    std::vector<PointLoad> loads;
    Anchoring anchoring;
    int resolution = 80, cells = 16, r = 15;
    if (!bench::QuickRun()) {
      const auto file = FindDataFile("armadillo.obj");
      if (!file) throw Error("bench_deformed_field: data/meshes/armadillo.obj.gz not found");
      MeshLoadOptions load;
      load.center = true;
      mesh = LoadMesh(*file, load);
      mesh.Transform(0.2 / mesh.Bounds().size().y(), Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
      loads = {{Eigen::Vector3d(-0.0295, -0.078, -0.026), -Eigen::Vector3d::UnitX()},
               {Eigen::Vector3d(0.0427, -0.078, -0.018), Eigen::Vector3d::UnitX()}};
      anchoring = Anchoring::BelowPlane(-Eigen::Vector3d::UnitY(), 0.0);  // y >= 0 fixed
    } else {
      mesh = MakeBox(Eigen::Vector3d(0.02, 0.02, 0.1), 6);
      loads = {{Eigen::Vector3d(0, 0, -0.09), Eigen::Vector3d::UnitX()}};
      anchoring = Anchoring::BelowPlane(-Eigen::Vector3d::UnitZ(), -0.08);
      resolution = 32, cells = 8, r = 6;
    }
    DistanceFieldOptions fo;
    fo.resolution = resolution;
    fo.show_progress = false;
    s.field = std::make_shared<const DistanceField>(BuildDistanceField(mesh, fo));
    VoxelMeshOptions vo;
    vo.cells = cells;
    ReducedModelOptions mo;
    mo.modes = r;
    mo.kind = ReducedModelKind::kLinear;
    mo.material.youngs_modulus = 5e5;
    mo.material.poisson_ratio = 0.35;
    mo.material.density = 1000;
    mo.anchoring = anchoring;
    mo.show_progress = false;
    s.model = BuildReducedModel(BuildVoxelTetMesh(*s.field, vo), mo, mesh.name);
    const EmbeddedSurface surface(mesh, s.model.mesh, s.model.basis);
    s.q = SolveScaledPointLoadPose(s.model.forces, s.model.mesh, s.model.basis, loads, surface,
                                   0.1 * mesh.Bounds().size().maxCoeff(), "bench");
    // Band points of the deformed surface (the sampling of the fig10 study).
    const MeshSignedDistance exact(surface.Deformed(s.q), "bench");
    const DeformedDistanceField field(s.field, s.model.mesh, s.model.basis, DeformedFieldOptions{}, "bench");
    DeformedFieldState state(field);
    state.Update(field, s.q.data());
    BandErrorOptions bo;
    bo.band = 2 * s.field->spacing();
    bo.points = 4096;
    s.points = MeasureBandError(field, state, exact, bo, "bench").band_points;
    return s;
  }();
  return setup;
}

// Fields are built once per (proxies, k, domains).
const DeformedDistanceField& GetField(int proxies, int k, int domains) {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<DeformedDistanceField>> cache;
  auto& slot = cache[{proxies, k, domains}];
  if (!slot) {
    const Setup& s = GetSetup();
    DeformedFieldOptions o;
    o.proxies = proxies;
    o.neighbours = k;
    o.domains = domains;
    slot = std::make_unique<DeformedDistanceField>(s.field, s.model.mesh, s.model.basis, o, "bench");
  }
  return *slot;
}

// The indices of POINTS (x, y, z triples) sorted along a Morton curve of 2 mm cells: a spatially
// coherent order, the way a pointshell traversal issues its queries.
std::vector<std::size_t> MortonOrder(const std::vector<float>& points) {
  const std::size_t n = points.size() / 3;
  auto morton = [&](std::size_t i) {
    std::uint64_t code = 0;
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t v = std::uint64_t(std::max(0.f, (points[3 * i + c] + 0.5f) / 0.002f)) & 0x1fffff;
      for (int b = 0; b < 21; ++b) code |= ((v >> b) & 1u) << (3 * b + c);
    }
    return code;
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return morton(a) < morton(b); });
  return order;
}

// One Distance at band points of the deformed body. Args: proxies, k, domains.
void BM_Query(benchmark::State& state) {
  const Setup& s = GetSetup();
  const DeformedDistanceField& field = GetField(int(state.range(0)), int(state.range(1)), int(state.range(2)));
  DeformedFieldState fs(field);
  fs.Update(field, s.q.data());
  const std::size_t n = s.points.size() / 3;  // 4096, a power of two
  std::size_t i = 0;
  for (auto _ : state) {
    float d = field.Distance(fs, &s.points[3 * i], nullptr);
    benchmark::DoNotOptimize(d);
    i = (i + 1) & (n - 1);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["slots"] = field.num_slots();
  state.counters["r"] = field.r();
}
BENCHMARK(BM_Query)
    ->Args({40, 5, 1})   // the paper's setting and the target (<= 150 ns)
    ->Args({20, 5, 1})   // fewer proxies: a shorter scan
    ->Args({80, 5, 1})   // more proxies: a longer scan
    ->Args({40, 3, 1})   // k = 3: two field lookups
    ->Args({40, 8, 1})   // k = 8: seven field lookups
    ->Args({40, 5, 3})   // three automatic domains: three scans and 3 (k - 1) lookups
    ->Unit(benchmark::kNanosecond);

// The same queries in a spatially coherent order (sorted along a Morton curve of 2 mm cells), as
// a pointshell traversal issues them: the field lookups hit the cache more often. Args as above.
void BM_QueryCoherent(benchmark::State& state) {
  const Setup& s = GetSetup();
  const DeformedDistanceField& field = GetField(int(state.range(0)), int(state.range(1)), int(state.range(2)));
  DeformedFieldState fs(field);
  fs.Update(field, s.q.data());
  const std::size_t n = s.points.size() / 3;
  const std::vector<std::size_t> order = MortonOrder(s.points);
  std::vector<float> points(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) points[3 * i + c] = s.points[3 * order[i] + c];
  }
  std::size_t i = 0;
  for (auto _ : state) {
    float d = field.Distance(fs, &points[3 * i], nullptr);
    benchmark::DoNotOptimize(d);
    i = (i + 1) & (n - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QueryCoherent)
    ->Args({40, 5, 1})  // the paper's setting, coherent order
    ->Args({40, 3, 1})  // k = 3
    ->Unit(benchmark::kNanosecond);

// The many-point query (deform/deformed_field_batch.h) over the same band points, a batch of 256
// per call as the contact model issues them. Args: proxies, k, domains, order (0 as BM_Query,
// 1 the Morton order of BM_QueryCoherent). Counter ns_per_query.
void BM_QueryBatch(benchmark::State& state) {
  const Setup& s = GetSetup();
  const DeformedDistanceField& field = GetField(int(state.range(0)), int(state.range(1)), int(state.range(2)));
  DeformedFieldState fs(field);
  fs.Update(field, s.q.data());
  const std::size_t n = s.points.size() / 3;
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  if (state.range(3) == 1) order = MortonOrder(s.points);
  std::vector<float> x(n), y(n), z(n), d(n);
  std::vector<std::int32_t> nearest(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = s.points[3 * order[i]], y[i] = s.points[3 * order[i] + 1], z[i] = s.points[3 * order[i] + 2];
  }
  constexpr std::size_t kBatch = 256;
  std::size_t i = 0;
  std::int64_t answered = 0;
  for (auto _ : state) {
    answered += DeformedFieldDistances(field, fs, &x[i], &y[i], &z[i], int(kBatch), &d[i], &nearest[i]);
    benchmark::DoNotOptimize(d.data());
    i = (i + kBatch) & (n - 1);
  }
  const double queries = double(state.iterations()) * double(kBatch);
  state.SetItemsProcessed(std::int64_t(queries));
  state.counters["ns_per_query"] =
      benchmark::Counter(queries * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // Domains queried per point (the rest culled by their lower bounds).
  state.counters["domains_per_query"] = double(answered) / queries;
}
BENCHMARK(BM_QueryBatch)
    ->Args({40, 5, 1, 0})  // the target: <= 60 ns
    ->Args({40, 5, 1, 1})
    ->Args({20, 5, 1, 0})
    ->Args({80, 5, 1, 0})
    ->Args({40, 3, 1, 0})
    ->Args({40, 8, 1, 0})
    ->Args({40, 5, 3, 0})  // three domains: <= 3 x one, less where the domains' bounds cull
    ->Args({40, 5, 3, 1})
    ->Args({40, 5, 5, 0})  // five domains, as the armadillo of the defo-defo scene
    ->Args({40, 5, 5, 1})
    ->Unit(benchmark::kMicrosecond);

// DeformedFieldState::Update: every proxy slot's position and pull-back at q (once per cycle).
// Args: proxies, domains.
void BM_Update(benchmark::State& state) {
  const Setup& s = GetSetup();
  const DeformedDistanceField& field = GetField(int(state.range(0)), 5, int(state.range(1)));
  DeformedFieldState fs(field);
  for (auto _ : state) {
    fs.Update(field, s.q.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * field.num_slots());
  state.counters["slots"] = field.num_slots();
  state.counters["r"] = field.r();
}
BENCHMARK(BM_Update)
    ->Args({40, 1})  // the paper's 40 proxies, one domain
    ->Args({40, 3})  // three domains: shared proxies repeat in each domain's slots
    ->Args({80, 1})  // twice the proxies
    ->Unit(benchmark::kNanosecond);

// --- k nearest deformed proxies: brute-force scan against a k-d tree rebuilt every cycle ---

// The deformed positions of the one-domain field's 40 (or N) proxies, structure of arrays.
struct ProxyCloud {
  std::vector<float> x, y, z;
  std::size_t kdtree_get_point_count() const { return x.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return dim == 0 ? x[i] : dim == 1 ? y[i] : z[i]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, ProxyCloud>, ProxyCloud, 3,
                                                   std::uint32_t>;

ProxyCloud DeformedProxies(int proxies) {
  const Setup& s = GetSetup();
  const DeformedDistanceField& field = GetField(proxies, 5, 1);
  DeformedFieldState fs(field);
  fs.Update(field, s.q.data());
  ProxyCloud c;
  for (int i = 0; i < field.num_slots(); ++i) {
    c.x.push_back(fs.position(i)[0]);
    c.y.push_back(fs.position(i)[1]);
    c.z.push_back(fs.position(i)[2]);
  }
  return c;
}

// The scan of DeformedDistanceField: squared distances, insertion into a sorted list of k.
inline int BruteKnn(const ProxyCloud& c, const float* x, int k, std::uint32_t* idx, float* d2) {
  int n = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const float dx = x[0] - c.x[i], dy = x[1] - c.y[i], dz = x[2] - c.z[i];
    const float e = dx * dx + dy * dy + dz * dz;
    if (n == k && !(e < d2[k - 1])) continue;
    int m = n < k ? n++ : k - 1;
    while (m > 0 && d2[m - 1] > e) {
      d2[m] = d2[m - 1];
      idx[m] = idx[m - 1];
      --m;
    }
    d2[m] = e;
    idx[m] = std::uint32_t(i);
  }
  return n;
}

// One cycle: QUERIES k-nearest searches by brute force (nothing to rebuild). Items: queries.
// Args: proxies, k, queries per cycle.
void BM_KnnBruteForce(benchmark::State& state) {
  const Setup& s = GetSetup();
  const ProxyCloud cloud = DeformedProxies(int(state.range(0)));
  const int k = int(state.range(1)), queries = int(state.range(2));
  const std::size_t n = s.points.size() / 3;
  std::uint32_t idx[kMaxProxyNeighbours];
  float d2[kMaxProxyNeighbours];
  std::size_t p = 0;
  for (auto _ : state) {
    for (int i = 0; i < queries; ++i) {
      benchmark::DoNotOptimize(BruteKnn(cloud, &s.points[3 * p], k, idx, d2));
      benchmark::DoNotOptimize(idx[0]);
      p = (p + 1) & (n - 1);
    }
  }
  state.SetItemsProcessed(state.iterations() * queries);
}
BENCHMARK(BM_KnnBruteForce)
    ->Args({40, 5, 1000})  // the paper's proxies and k, ~1000 queries a cycle
    ->Args({40, 5, 100})   // a cycle with few contact queries
    ->Args({80, 5, 1000})  // twice the proxies
    ->Args({160, 5, 1000}) // where a tree might start to pay off
    ->Unit(benchmark::kNanosecond);

// The scan in two passes: all squared distances first (structure of arrays, a loop the compiler
// vectorises), then the insertion only for those below the current k-th. Args as above.
void BM_KnnTwoPass(benchmark::State& state) {
  const Setup& s = GetSetup();
  const ProxyCloud cloud = DeformedProxies(int(state.range(0)));
  const int k = int(state.range(1)), queries = int(state.range(2));
  const std::size_t n = s.points.size() / 3, m = cloud.x.size();
  std::vector<float> e(m);
  std::uint32_t idx[kMaxProxyNeighbours];
  float d2[kMaxProxyNeighbours];
  std::size_t p = 0;
  for (auto _ : state) {
    for (int q = 0; q < queries; ++q) {
      const float* x = &s.points[3 * p];
      const float x0 = x[0], x1 = x[1], x2 = x[2];
      for (std::size_t i = 0; i < m; ++i) {
        const float dx = x0 - cloud.x[i], dy = x1 - cloud.y[i], dz = x2 - cloud.z[i];
        e[i] = dx * dx + dy * dy + dz * dz;
      }
      int c = 0;
      for (std::size_t i = 0; i < m; ++i) {
        const float v = e[i];
        if (c == k && !(v < d2[k - 1])) continue;
        int j = c < k ? c++ : k - 1;
        while (j > 0 && d2[j - 1] > v) {
          d2[j] = d2[j - 1];
          idx[j] = idx[j - 1];
          --j;
        }
        d2[j] = v;
        idx[j] = std::uint32_t(i);
      }
      benchmark::DoNotOptimize(idx[0]);
      p = (p + 1) & (n - 1);
    }
  }
  state.SetItemsProcessed(state.iterations() * queries);
}
BENCHMARK(BM_KnnTwoPass)
    ->Args({40, 5, 1000})  // the paper's proxies and k
    ->Args({80, 5, 1000})  // twice the proxies
    ->Unit(benchmark::kNanosecond);

// The scan as k passes of a branch-free minimum over all squared distances (the found one
// masked out after each pass). Args as above.
void BM_KnnMinPasses(benchmark::State& state) {
  const Setup& s = GetSetup();
  const ProxyCloud cloud = DeformedProxies(int(state.range(0)));
  const int k = int(state.range(1)), queries = int(state.range(2));
  const std::size_t n = s.points.size() / 3, m = cloud.x.size();
  std::vector<float> e(m);
  std::uint32_t idx[kMaxProxyNeighbours];
  float d2[kMaxProxyNeighbours];
  std::size_t p = 0;
  for (auto _ : state) {
    for (int q = 0; q < queries; ++q) {
      const float* x = &s.points[3 * p];
      const float x0 = x[0], x1 = x[1], x2 = x[2];
      for (std::size_t i = 0; i < m; ++i) {
        const float dx = x0 - cloud.x[i], dy = x1 - cloud.y[i], dz = x2 - cloud.z[i];
        e[i] = dx * dx + dy * dy + dz * dz;
      }
      for (int j = 0; j < k; ++j) {
        float best = e[0];
        for (std::size_t i = 1; i < m; ++i) best = e[i] < best ? e[i] : best;
        std::size_t at = 0;
        while (e[at] != best) ++at;
        d2[j] = best;
        idx[j] = std::uint32_t(at);
        e[at] = std::numeric_limits<float>::infinity();
      }
      benchmark::DoNotOptimize(idx[0]);
      benchmark::DoNotOptimize(d2[0]);
      p = (p + 1) & (n - 1);
    }
  }
  state.SetItemsProcessed(state.iterations() * queries);
}
BENCHMARK(BM_KnnMinPasses)
    ->Args({40, 5, 1000})  // the paper's proxies and k
    ->Args({80, 5, 1000})  // twice the proxies
    ->Unit(benchmark::kNanosecond);

// One cycle: rebuild the k-d tree over the (moved) proxies, then QUERIES searches. Items:
// queries, so the rebuild is amortised over a cycle's queries. Args: proxies, k, queries per
// cycle, leaf size.
void BM_KnnKdTree(benchmark::State& state) {
  const Setup& s = GetSetup();
  const ProxyCloud cloud = DeformedProxies(int(state.range(0)));
  const int k = int(state.range(1)), queries = int(state.range(2));
  KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(std::size_t(state.range(3))));
  const std::size_t n = s.points.size() / 3;
  std::uint32_t idx[kMaxProxyNeighbours];
  float d2[kMaxProxyNeighbours];
  std::size_t p = 0;
  for (auto _ : state) {
    tree.buildIndex();  // the proxies moved: the tree is stale every cycle
    for (int i = 0; i < queries; ++i) {
      nanoflann::KNNResultSet<float, std::uint32_t> result{std::size_t(k)};
      result.init(idx, d2);
      tree.findNeighbors(result, &s.points[3 * p], nanoflann::SearchParams());
      benchmark::DoNotOptimize(idx[0]);
      p = (p + 1) & (n - 1);
    }
  }
  state.SetItemsProcessed(state.iterations() * queries);
}
BENCHMARK(BM_KnnKdTree)
    ->Args({40, 5, 1000, 4})   // 40 proxies, k = 5, 1000 queries a cycle, leaves of 4
    ->Args({40, 5, 1000, 10})  // leaves of 10 (nanoflann's default)
    ->Args({40, 5, 100, 4})    // few queries: the rebuild weighs more
    ->Args({80, 5, 1000, 4})   // twice the proxies
    ->Args({160, 5, 1000, 4})  // where a tree might start to pay off
    ->Unit(benchmark::kNanosecond);

// The rebuild alone (per cycle). Args: proxies, leaf size.
void BM_KdTreeRebuild(benchmark::State& state) {
  const ProxyCloud cloud = DeformedProxies(int(state.range(0)));
  KdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(std::size_t(state.range(1))));
  for (auto _ : state) {
    tree.buildIndex();
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_KdTreeRebuild)
    ->Args({40, 4})   // the paper's proxy count
    ->Args({160, 4})  // four times as many
    ->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace contactlab

CONTACTLAB_BENCHMARK_MAIN()
