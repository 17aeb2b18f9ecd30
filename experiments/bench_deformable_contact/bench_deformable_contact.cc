// Questions (issue 13, item 8; Barbič & James 2008, sec. 4.1 and Table 1): what does deforming
// the pointshell cost per visited node against the rigid model, for r = 5..40; what does the
// reduced StVK step cost inside the cycle, with the contact stiffness; and does the whole
// deformable cycle (query + step) on the bridge scene with a 256k-point pointshell stay within
// the 1 ms haptic budget (p99.9) under graceful degradation?
//
//   BM_PerNode     one Evaluate at a fixed pose; the rigid PointshellContactModel against
//                  DeformablePointshellContactModel at q = 0 (the same points, the same
//                  contact set: the pure cost of x = X + U q, n + N q, R(q) and U^T F) and at
//                  a realistic q (the bridge settled under the dragon's press, a few mm of
//                  displacement); linear traversal (every point) and tree traversal.
//                  Counter ns_per_node (CPU time / nodes visited).
//   BM_StreamBasis the bound of the linear traversal: read every point's rows of U (as the
//                  deformed positions do) and the rest positions, nothing else. Counters
//                  ns_per_point and GBps (bytes of U and X read per second).
//   BM_Step        ReducedIntegrator::Step(f, &K) with the reduced contact force and stiffness
//                  of the settled configuration, against Step(f) without K.
//   BM_Cycle       the coupled loop of contactlab run (query with q held fixed, then
//                  Step(f, &K)) along a trajectory of the dragon pressed into the bridge and
//                  slid across it and back; one iteration per haptic cycle, so the run is the
//                  whole trajectory. Counters: p50_us/p99_us/p999_us/max_us (wall clock per
//                  cycle), cpu_p50_us/cpu_p999_us/cpu_max_us (the thread's CPU time per cycle:
//                  not inflated when another process takes the core), step_us, nodes and level
//                  (means), min_level, over_1ms (cycles), u_peak_mm (largest displacement).
//
// Every benchmark reports allocs: heap allocations made inside its timed loop (must be 0).
//
// Quick mode (CONTACTLAB_BENCH_QUICK=1): the cantilever-probe scene with a 1024-point shell, a
// coarse tet mesh and r = 5 and 10, and a 300-cycle trajectory.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include <time.h>

#include "bench_common.h"
#include "bench_main.h"
#include "placed_scene.h"
#include "pointshell_contact/deformable_contact_models.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "deform/reduced_integrator.h"
#include "deform/reduced_point_batch.h"
#include "scene/contact_placement.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "util/data_path.h"
#include "util/error.h"

// Heap allocations made by this program, so the timed loops can report that they made none.
// (GCC cannot see that the replaced operator new allocates with malloc.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
std::atomic<long long> g_allocations{0};
}  // namespace
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace contactlab {
namespace {

// ---------------------------------------------------------------------------------------------
// Scenes: a deformable pointshell body A pressed by a rigid field body B.

// How a scene is pressed and slid: B moves along PRESS into A, then along SLIDE across it.
struct SceneCase {
  std::string file;
  int points = 0, levels = 0;  // pointshell overrides (0: the scene's)
  int cells = 0;               // tet mesh override (0: the scene's)
  int field_resolution = 0;    // override for both bodies' fields (0: the scene's)
  Eigen::Vector3d press{0, -1, 0};
  Eigen::Vector3d slide{1, 0, 0};
  double press_depth = 0;      // into A at rest, metres
  double slide_half = 0;       // B slides over [-slide_half, slide_half] along SLIDE, metres
};

// PRESS_DEPTH into the rest bridge; the bridge yields, so the dragon's penetration stays
// smaller (at 4 mm the bridge settles ~2.3 mm down under the dragon).
SceneCase BridgeCase(int points, int levels, double press_depth = 0.004) {
  SceneCase c;
  c.file = "scenes/bridge-dragon.yaml";
  c.points = points;
  c.levels = levels;
  c.press_depth = press_depth;
  c.slide_half = 0.06;    // +-6 cm of the 26 cm free span
  return c;
}

SceneCase CantileverCase() {  // quick mode
  SceneCase c;
  c.file = "scenes/cantilever-probe.yaml";
  c.points = 1024;
  c.levels = 3;
  c.cells = 20;
  c.field_resolution = 64;
  c.press = Eigen::Vector3d(0, 0, -1);
  c.press_depth = 0.002;
  c.slide_half = 0.01;
  return c;
}

// One scene at one r, with B placed at SLIDE offset 0 and the press depth, and the state q the
// coupled loop settles to there.
struct Prepared {
  Scene scene;
  std::unique_ptr<SceneAssets> assets;
  Pose X_WA, X_WB_touch, X_WB;  // A; B just touching A at rest; B pressed PRESS_DEPTH in
  ReducedState settled;         // q after the coupled loop settled at X_WB
  ReducedVector f_settled;      // reduced contact force and stiffness there
  ReducedMatrix K_settled;
  double u_max = 0;             // largest point displacement |U_i q| at the settled q, metres
  int contacts_settled = 0;
};

IntegratorOptions IntegratorFor(const Scene& scene) {
  const DeformableSpec& d = *scene.pointshell_body.deformable;
  IntegratorOptions o;
  o.time_step = scene.model.cycle_seconds;
  o.mass_damping = d.mass_damping;
  o.stiffness_damping = d.stiffness_damping;
  return o;
}

double MaxDisplacement(const EmbeddedPoints& points, const ReducedVector& q) {
  double max2 = 0;
  for (int i = 0; i < points.size(); ++i) max2 = std::max(max2, points.Displacement(i, q.data()).squaredNorm());
  return std::sqrt(max2);
}

// Loads, places and settles case C at R modes, once per program run. Throws Error.
Prepared& Prepare(const SceneCase& c, int r, ReducedModelKind kind = ReducedModelKind::kStVK) {
  static std::map<std::string, std::unique_ptr<Prepared>> cache;
  const std::string key = c.file + "/" + std::to_string(c.points) + "/" + std::to_string(c.levels) + "/" +
                          std::to_string(c.press_depth) + "/" + std::to_string(r) + "/" + std::to_string(int(kind));
  if (auto it = cache.find(key); it != cache.end()) return *it->second;
  auto prepared = std::make_unique<Prepared>();  // kept only once complete
  Prepared& p = *prepared;
  p.scene = LoadScene(RequireDataFile(c.file));
  BodySpec& a = p.scene.pointshell_body;
  if (c.points > 0) a.pointshell.points = c.points;
  if (c.levels > 0) a.pointshell.levels = c.levels;
  if (c.field_resolution > 0) a.field.resolution = p.scene.field_body.field.resolution = c.field_resolution;
  a.deformable->modes = r;
  a.deformable->kind = kind;
  if (c.cells > 0) a.deformable->cells = c.cells;
  AssetOptions options;
  options.verbose = false;
  p.assets = std::make_unique<SceneAssets>(p.scene, options);
  p.X_WA = a.pose;
  // B where it just touches A at rest (found 1 mm deep, then backed off 1 mm along PRESS), and
  // B pressed PRESS_DEPTH further along PRESS. (TouchAlong marches in steps of a quarter of
  // the depth it is asked for, and the dragon's feet are thinner than the deepest press, so
  // neither a bare touch nor the press depth itself is asked for.)
  constexpr double kTouchDepth = 0.001;
  p.X_WB_touch = TouchAlong(p.scene, *p.assets, /*move_B=*/true, p.X_WA, p.scene.field_body.pose, c.press,
                            kTouchDepth, c.file);
  p.X_WB_touch.translation -= kTouchDepth * c.press.normalized();
  p.X_WB = p.X_WB_touch;
  p.X_WB.translation += c.press_depth * c.press.normalized();

  // Settle the coupled loop at the pressed pose (2 s of simulated time).
  const auto model = p.assets->A.reduced_model();
  DeformablePointshellContactModel contact(DeformablePointshellContactModel::Variant::kTree,
                                           p.assets->A.deformable_pointshell(), p.assets->B.field(), PaperModelParams(p.scene));
  ReducedIntegrator integrator(model->forces, IntegratorFor(p.scene));
  ReducedVector f = ReducedVector::Zero(r);
  ReducedMatrix K = ReducedMatrix::Zero(r, r);
  ContactQuery q;
  q.X_WA = p.X_WA;
  q.X_WB = p.X_WB;
  BodyDeformation deformation{nullptr, &f, &K};
  q.deformation_A = &deformation;
  const int settle_cycles = bench::QuickRun() ? 200 : 2000;
  for (int k = 0; k < settle_cycles; ++k) {
    q.cycle = k;
    deformation.q = &integrator.state();
    const ContactResult res = contact.Evaluate(q);
    p.contacts_settled = res.stats.points_in_contact;
    integrator.Step(f, &K);
  }
  p.settled = integrator.state();
  deformation.q = &p.settled;
  contact.Evaluate(q);
  p.f_settled = f;
  p.K_settled = K;
  p.u_max = MaxDisplacement(p.assets->A.deformable_pointshell()->points(), p.settled.q);
  return *(cache[key] = std::move(prepared));
}

// Null (and STATE skipped with the error's message) when the case cannot be prepared.
Prepared* TryPrepare(benchmark::State& state, const SceneCase& c, int r,
                     ReducedModelKind kind = ReducedModelKind::kStVK) {
  try {
    return &Prepare(c, r, kind);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
    return nullptr;
  }
}

std::vector<int> ModeCounts() { return bench::QuickRun() ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 15, 20, 40}; }

SceneCase PerNodeCase() { return bench::QuickRun() ? CantileverCase() : BridgeCase(0, 0); }  // bridge: 16384 points, 5 levels

// ---------------------------------------------------------------------------------------------
// 1. Per visited node: rigid against deformable.

enum Shell { kRigid, kDeformableAtRest, kDeformableSettled };
const char* const kShellNames[] = {"rigid", "deformable-q0", "deformable-settled"};

void BM_PerNode(benchmark::State& state, SceneCase c, int r, Shell shell, PointshellContactModel::Variant variant) {
  Prepared* prepared = TryPrepare(state, c, r);
  if (prepared == nullptr) return;
  Prepared& p = *prepared;
  std::unique_ptr<ContactModel> model;
  if (shell == kRigid) {
    model = std::make_unique<PointshellContactModel>(variant, p.assets->A.pointshell(), p.assets->B.field(), PaperModelParams(p.scene));
  } else {
    model = std::make_unique<DeformablePointshellContactModel>(variant, p.assets->A.deformable_pointshell(),
                                                               p.assets->B.field(), PaperModelParams(p.scene));
  }
  // The cycle's query: reduced force and stiffness wanted from the deformable model.
  const ReducedState rest(r);
  ReducedVector f = ReducedVector::Zero(r);
  ReducedMatrix K = ReducedMatrix::Zero(r, r);
  ContactQuery q;
  q.X_WA = p.X_WA;
  q.X_WB = p.X_WB;
  const BodyDeformation deformation{shell == kDeformableSettled ? &p.settled : &rest, &f, &K};
  if (shell != kRigid) q.deformation_A = &deformation;
  double nodes = 0, contacts = 0;
  const long long allocations = g_allocations.load();
  for (auto _ : state) {
    const ContactResult res = model->Evaluate(q);
    benchmark::DoNotOptimize(res);
    benchmark::DoNotOptimize(f.data());
    nodes += double(res.stats.nodes_visited);
    contacts += res.stats.points_in_contact;
    ++q.cycle;
  }
  const double n = double(std::max<benchmark::IterationCount>(1, state.iterations()));
  state.counters["allocs"] = double(g_allocations.load() - allocations);
  state.counters["nodes"] = nodes / n;
  state.counters["contacts"] = contacts / n;
  state.counters["u_max_mm"] = shell == kDeformableSettled ? 1e3 * p.u_max : 0.0;
  state.counters["ns_per_node"] =
      benchmark::Counter(nodes * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetItemsProcessed(std::int64_t(nodes));
}

// The bandwidth bound of the linear traversal: every point's three rows of U and its rest
// position streamed through vector loads (deform/reduced_point_batch.h), summed so nothing is
// skipped.
void BM_StreamBasis(benchmark::State& state, SceneCase c, int r) {
  Prepared* prepared = TryPrepare(state, c, r);
  if (prepared == nullptr) return;
  const DeformablePointshell& shell = *prepared->assets->A.deformable_pointshell();
  const EmbeddedPoints& P = shell.points();
  const Pointshell& s = shell.shell();
  const int n = s.level_point_end[s.num_levels() - 1];
  const std::size_t bytes = sizeof(float) * (3 * std::size_t(P.basis_stride()) + 3) * std::size_t(n);
  for (auto _ : state) benchmark::DoNotOptimize(StreamPointRows(P, s.x.data(), s.y.data(), s.z.data(), n));
  const double iterations = double(std::max<benchmark::IterationCount>(1, state.iterations()));
  state.counters["ns_per_point"] =
      benchmark::Counter(double(n) * iterations * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["GBps"] = benchmark::Counter(double(bytes) * iterations * 1e-9, benchmark::Counter::kIsRate);
  state.counters["MB"] = 1e-6 * double(bytes);
}

// ---------------------------------------------------------------------------------------------
// 2. The reduced step inside the cycle, with and without the contact stiffness.

void BM_Step(benchmark::State& state, SceneCase c, int r, ReducedModelKind kind, bool with_K) {
  Prepared* prepared = TryPrepare(state, c, r, kind);
  if (prepared == nullptr) return;
  Prepared& p = *prepared;
  const auto model = p.assets->A.reduced_model();
  ReducedIntegrator integrator(model->forces, IntegratorFor(p.scene));
  integrator.SetState(p.settled);
  ReducedVector f(r);
  std::int64_t k = 0;
  const long long allocations = g_allocations.load();
  for (auto _ : state) {
    // The settled contact load, wobbling so q keeps moving near the settled state.
    f = (1.0 + 0.1 * std::sin(1e-2 * double(k++))) * p.f_settled;
    benchmark::DoNotOptimize(integrator.Step(f, with_K ? &p.K_settled : nullptr));
    benchmark::DoNotOptimize(integrator.state().q.data());
  }
  state.counters["allocs"] = double(g_allocations.load() - allocations);
  state.SetItemsProcessed(state.iterations());
}

// ---------------------------------------------------------------------------------------------
// 3. The whole deformable cycle along a trajectory.

// B's pose at cycle K of the trajectory: pressed in along PRESS over the first PRESS_CYCLES
// (from 1 mm clear of A to PRESS_DEPTH), then slid from -SLIDE_HALF to +SLIDE_HALF and back.
struct Trajectory {
  Pose X_WB_touch;
  Eigen::Vector3d press, slide;
  double depth = 0, half = 0;
  std::int64_t press_cycles = 0, slide_cycles = 0;
  std::int64_t cycles() const { return press_cycles + 2 * slide_cycles; }
  Pose At(std::int64_t k) const {
    double s, x;
    if (k < press_cycles) {
      s = -0.001 + (depth + 0.001) * double(k) / double(press_cycles);
      x = -half;
    } else {
      s = depth;
      const double u = double(k - press_cycles) / double(slide_cycles);  // 0..2
      x = u <= 1 ? -half + 2 * half * u : half - 2 * half * (u - 1);
    }
    Pose X = X_WB_touch;
    X.translation += s * press + x * slide;
    return X;
  }
};

// CPU time of the calling thread, microseconds: unlike the wall clock it does not count the
// time another process held the core (the machine may be shared).
double ThreadCpuMicros() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e6 * double(t.tv_sec) + 1e-3 * double(t.tv_nsec);
}

double Percentile(const std::vector<double>& sorted, double p) {
  return sorted[std::size_t(std::llround(p * double(sorted.size() - 1)))];
}

void BM_Cycle(benchmark::State& state, SceneCase c, int r, std::int64_t budget, bool coherence,
              std::int64_t press_cycles, std::int64_t slide_cycles) {
  Prepared* prepared = TryPrepare(state, c, r);
  if (prepared == nullptr) return;
  Prepared& p = *prepared;
  const auto reduced = p.assets->A.reduced_model();
  PointshellContactParams params = PaperModelParams(p.scene);
  params.coherence = coherence;
  DeformablePointshellContactModel model(DeformablePointshellContactModel::Variant::kTree,
                                         p.assets->A.deformable_pointshell(), p.assets->B.field(), params);
  ReducedIntegrator integrator(reduced->forces, IntegratorFor(p.scene));
  Trajectory traj{p.X_WB_touch, c.press.normalized(), c.slide.normalized(), c.press_depth, c.slide_half,
                  press_cycles, slide_cycles};

  // Scratch sized once: per-cycle times and the reduced force/stiffness the query fills.
  const std::int64_t cycles = traj.cycles();
  std::vector<double> cycle_us(std::size_t(cycles), 0.0), query_us(std::size_t(cycles), 0.0),
      cpu_us(std::size_t(cycles), 0.0);
  ReducedVector f = ReducedVector::Zero(r), q_peak = ReducedVector::Zero(r);
  ReducedMatrix K = ReducedMatrix::Zero(r, r);
  double nodes = 0, level = 0, contacts = 0, step_us = 0, q_peak_norm = 0, max_pen = 0;
  int min_level = 1 << 30;
  ContactQuery q;
  q.X_WA = p.X_WA;
  q.node_budget = budget;
  BodyDeformation deformation{nullptr, &f, &K};
  q.deformation_A = &deformation;
  std::int64_t k = 0;
  const long long allocations = g_allocations.load();
  for (auto _ : state) {
    if (k == cycles) {  // only with a --benchmark_min_time that asks for more: start over
      state.SkipWithError("the trajectory is shorter than the iterations asked for");
      break;
    }
    const double c0 = ThreadCpuMicros();
    const auto t0 = std::chrono::steady_clock::now();
    // One haptic cycle: traverse with the deformation held fixed, then step.
    q.X_WB = traj.At(k);
    q.cycle = k;
    deformation.q = &integrator.state();
    const ContactResult res = model.Evaluate(q);
    const auto t1 = std::chrono::steady_clock::now();
    integrator.Step(f, &K);
    const auto t2 = std::chrono::steady_clock::now();
    cpu_us[std::size_t(k)] = ThreadCpuMicros() - c0;
    cycle_us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t2 - t0).count();
    query_us[std::size_t(k)] = std::chrono::duration<double, std::micro>(t1 - t0).count();
    step_us += std::chrono::duration<double, std::micro>(t2 - t1).count();
    nodes += double(res.stats.nodes_visited);
    level += res.stats.level_rendered;
    min_level = std::min(min_level, int(res.stats.level_rendered));
    contacts += res.stats.points_in_contact;
    max_pen = std::max(max_pen, res.stats.max_penetration);
    const double qn = integrator.state().q.squaredNorm();
    if (qn > q_peak_norm) {
      q_peak_norm = qn;
      q_peak = integrator.state().q;
    }
    ++k;
  }
  const long long allocs = g_allocations.load() - allocations;
  if (k == 0) return;
  cycle_us.resize(std::size_t(k));
  query_us.resize(std::size_t(k));
  cpu_us.resize(std::size_t(k));
  double mean = 0;
  for (double t : cycle_us) mean += t;
  std::sort(cycle_us.begin(), cycle_us.end());
  std::sort(query_us.begin(), query_us.end());
  std::sort(cpu_us.begin(), cpu_us.end());
  const double n = double(k);
  state.counters["allocs"] = double(allocs);
  state.counters["cycles"] = n;
  state.counters["mean_us"] = mean / n;
  state.counters["p50_us"] = Percentile(cycle_us, 0.5);
  state.counters["p99_us"] = Percentile(cycle_us, 0.99);
  state.counters["p999_us"] = Percentile(cycle_us, 0.999);
  state.counters["max_us"] = cycle_us.back();
  state.counters["cpu_p50_us"] = Percentile(cpu_us, 0.5);
  state.counters["cpu_p999_us"] = Percentile(cpu_us, 0.999);
  state.counters["cpu_max_us"] = cpu_us.back();
  state.counters["query_p999_us"] = Percentile(query_us, 0.999);
  state.counters["over_1ms"] = double(cycle_us.end() - std::upper_bound(cycle_us.begin(), cycle_us.end(), 1000.0));
  state.counters["step_us"] = step_us / n;
  state.counters["nodes"] = nodes / n;
  state.counters["level"] = level / n;
  state.counters["min_level"] = min_level;
  state.counters["contacts"] = contacts / n;
  state.counters["max_pen_mm"] = 1e3 * max_pen;
  state.counters["u_peak_mm"] = 1e3 * MaxDisplacement(p.assets->A.deformable_pointshell()->points(), q_peak);
  state.SetItemsProcessed(k);
}

// ---------------------------------------------------------------------------------------------

void RegisterAll() {
  const bool quick = bench::QuickRun();
  using Variant = PointshellContactModel::Variant;
  const std::vector<int> rs = ModeCounts();

  // 1. Per node, on the scene's 16384-point bridge for every r, and (full runs) on the
  // 262144-point bridge at r = 15, where U no longer fits in the caches. The rigid model does
  // not depend on r: one row per shell and traversal.
  struct NodeCase {
    SceneCase scene;
    std::vector<int> rs;
  };
  std::vector<NodeCase> node_cases = {{PerNodeCase(), rs}};
  if (!quick) node_cases.push_back({BridgeCase(262144, 6), {15}});
  for (const NodeCase& nc : node_cases) {
    const std::string points = std::to_string(nc.scene.points > 0 ? nc.scene.points : 16384);
    for (Variant variant : {Variant::kLinear, Variant::kTree}) {
      const std::string prefix =
          "per_node/points:" + points + (variant == Variant::kLinear ? "/linear/" : "/tree/");
      benchmark::RegisterBenchmark((prefix + "rigid").c_str(), BM_PerNode, nc.scene, nc.rs[0], kRigid, variant)
          ->Unit(benchmark::kMicrosecond);
      if (variant == Variant::kLinear) {
        const int r = std::find(nc.rs.begin(), nc.rs.end(), 15) != nc.rs.end() ? 15 : nc.rs.back();
        benchmark::RegisterBenchmark(("stream_basis/points:" + points + "/r:" + std::to_string(r)).c_str(),
                                     BM_StreamBasis, nc.scene, r)
            ->Unit(benchmark::kMicrosecond);
      }
      for (int r : nc.rs) {
        for (Shell shell : {kDeformableAtRest, kDeformableSettled}) {
          benchmark::RegisterBenchmark((prefix + kShellNames[shell] + "/r:" + std::to_string(r)).c_str(), BM_PerNode,
                                       nc.scene, r, shell, variant)
              ->Unit(benchmark::kMicrosecond);
        }
      }
    }
  }

  // 2. The step inside the cycle: reduced StVK at r = 15 and 20 (quick: 5, 10), with and
  // without the contact stiffness; and linear modal, whose pre-factored Jacobian K_ext breaks.
  const std::vector<int> step_rs = quick ? std::vector<int>{5, 10} : std::vector<int>{15, 20};
  for (int r : step_rs) {
    for (ReducedModelKind kind : {ReducedModelKind::kStVK, ReducedModelKind::kLinear}) {
      if (kind == ReducedModelKind::kLinear && r != step_rs.back()) continue;
      for (bool with_K : {false, true}) {
        const std::string name = std::string("step/") + (kind == ReducedModelKind::kStVK ? "stvk" : "linear") +
                                 "/r:" + std::to_string(r) + (with_K ? "/with_K" : "/no_K");
        benchmark::RegisterBenchmark(name.c_str(), BM_Step, PerNodeCase(), r, kind, with_K)
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }

  // 3. The whole cycle: the bridge with a 262144-point pointshell (6 levels), r = 15; 0.5 s
  // press, then 2 x 2.5 s of sliding over +-6 cm (5500 cycles), pressed 4 mm and 10 mm into
  // the rest bridge. Node budgets around the warm threshold V_W = 5000; 0 = unlimited (no
  // graceful degradation).
  std::vector<SceneCase> cycle_cases;
  if (quick) {
    cycle_cases = {CantileverCase()};
  } else {
    cycle_cases = {BridgeCase(262144, 6, 0.004), BridgeCase(262144, 6, 0.010)};
  }
  const std::int64_t press = quick ? 50 : 500, slide = quick ? 125 : 2500;
  const int cycle_r = quick ? 5 : 15;
  const std::vector<std::int64_t> budgets =
      quick ? std::vector<std::int64_t>{200, 0} : std::vector<std::int64_t>{2500, 5000, 10000, 20000, 0};
  for (const SceneCase& cc : cycle_cases) {
    for (bool coherence : {false, true}) {
      for (std::int64_t budget : budgets) {
        const std::string name = "cycle/points:" + std::to_string(cc.points) + "/r:" + std::to_string(cycle_r) +
                                 "/press_mm:" + std::to_string(int(std::lround(1e3 * cc.press_depth))) +
                                 "/budget:" + std::to_string(budget) + (coherence ? "/coherence" : "/no_coherence");
        benchmark::RegisterBenchmark(name.c_str(), BM_Cycle, cc, cycle_r, budget, coherence, press, slide)
            ->Iterations(press + 2 * slide)  // exactly one pass of the trajectory
            ->Unit(benchmark::kMicrosecond);
      }
    }
  }
}

}  // namespace
}  // namespace contactlab

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  contactlab::RegisterAll();
  return contactlab::bench::RunBenchmarks();
}
