// How long do the reduced deformable model's precomputation and its per-haptic-cycle work take
// (Barbič & James 2008, sec. 4.1: "much less than 100 us per time step")? Precomputation for
// r = 15 and 20 on a voxelised dragon rooted at its base (a few thousand tets); one implicit
// Newmark step, the reduced force/stiffness polynomials, and embedded point queries.
// Quick mode (CONTACTLAB_BENCH_QUICK=1): a small procedural beam instead of the dragon.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "bench_common.h"
#include "bench_main.h"
#include "deform/embedded_points.h"
#include "deform/reduced_integrator.h"
#include "deform/reduced_model.h"
#include "geometry/mesh_io.h"
#include "sdf/build_distance_field.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

struct Scene {
  std::string name;
  TetMesh mesh;
  Anchoring anchoring;
};

// The dragon voxelised at 24 cells and rooted at its base, or (quick run, or no shared data)
// a 12 x 3 x 3 beam anchored at one end.
const Scene& GetScene() {
  static const Scene scene = [] {
    Scene s;
    const auto dragon = FindDataFile("dragon.obj");
    if (!bench::QuickRun() && dragon) {
      MeshLoadOptions load;
      load.center = true;
      TriangleMesh mesh = LoadMesh(*dragon, load);
      const double extent = mesh.Bounds().size().maxCoeff();
      mesh.Transform(0.2 / extent, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());  // 20 cm long
      DistanceFieldOptions options;
      options.resolution = 96;
      options.show_progress = false;
      const DistanceField field = BuildDistanceField(mesh, options);
      VoxelMeshOptions voxel;
      voxel.cells = 24;
      s.mesh = BuildVoxelTetMesh(field, voxel);
      const Aabb b = s.mesh.Bounds();
      s.anchoring = Anchoring::BelowY(b.min.y() + 0.08 * b.size().y());
      s.name = "dragon";
    } else {
      s.mesh = MakeBoxTetMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0.25, 0.25), 12, 3, 3);
      s.anchoring = Anchoring::BelowPlane(Eigen::Vector3d::UnitX(), 1e-9);
      s.name = "beam";
    }
    return s;
  }();
  return scene;
}

ReducedModelOptions Options(int r, ReducedModelKind kind) {
  ReducedModelOptions o;
  o.modes = r;
  o.kind = kind;
  o.material.youngs_modulus = 1e6;
  o.material.poisson_ratio = 0.45;
  o.material.density = 1000;
  o.anchoring = GetScene().anchoring;
  o.show_progress = false;
  return o;
}

// Models are built once per (r, kind) and shared by the run-time benchmarks.
const ReducedModel& GetModel(int r, ReducedModelKind kind) {
  static std::map<std::pair<int, int>, std::unique_ptr<ReducedModel>> cache;
  auto& slot = cache[{r, int(kind)}];
  if (!slot) slot = std::make_unique<ReducedModel>(BuildReducedModel(GetScene().mesh, Options(r, kind), GetScene().name));
  return *slot;
}

void BM_Precompute(benchmark::State& state) {
  const int r = int(state.range(0));
  const auto kind = ReducedModelKind(state.range(1));
  const Scene& scene = GetScene();
  for (auto _ : state) {
    ReducedModel model = BuildReducedModel(scene.mesh, Options(r, kind), scene.name);
    benchmark::DoNotOptimize(model.basis.data());
  }
  state.counters["tets"] = scene.mesh.num_tets();
  state.counters["vertices"] = scene.mesh.num_vertices();
  state.SetItemsProcessed(state.iterations() * scene.mesh.num_tets());
}
BENCHMARK(BM_Precompute)
    ->Args({15, 0})  // reduced StVK, r = 15 (the paper's examples)
    ->Args({20, 0})  // reduced StVK, r = 20
    ->Args({20, 1})  // linear modal, r = 20
    ->Iterations(1)
    ->Unit(benchmark::kMicrosecond);

// One implicit Newmark step with NEWTON iterations under a small varying tip force.
void BM_TimeStep(benchmark::State& state) {
  const int r = int(state.range(0));
  const auto kind = ReducedModelKind(state.range(1));
  const ReducedModel& model = GetModel(r, kind);
  IntegratorOptions options;
  options.time_step = 1e-3;
  options.mass_damping = 0.5;
  options.stiffness_damping = 1e-3;
  options.newton_iterations = int(state.range(2));
  ReducedIntegrator integrator(model.forces, options);
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  ReducedVector f(r);
  for (int i = 0; i < r; ++i) f[i] = 0.5 * g(rng);
  ReducedVector f_ext(r);
  std::int64_t n = 0;
  for (auto _ : state) {
    f_ext = std::sin(1e-3 * double(n++)) * f;
    benchmark::DoNotOptimize(integrator.Step(f_ext));
    benchmark::DoNotOptimize(integrator.state().q.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TimeStep)
    ->Args({15, 0, 1})  // reduced StVK r = 15, one Newton iteration (the haptic-rate setting)
    ->Args({20, 0, 1})  // reduced StVK r = 20, one Newton iteration (target <= 20 us)
    ->Args({20, 0, 3})  // reduced StVK r = 20, three Newton iterations
    ->Args({20, 1, 1})  // linear modal r = 20 (pre-factored, constant stiffness)
    ->Unit(benchmark::kMicrosecond);

// The reduced internal force and tangent stiffness polynomials alone.
void BM_ReducedForces(benchmark::State& state) {
  const int r = int(state.range(0));
  const ReducedModel& model = GetModel(r, ReducedModelKind::kStVK);
  auto ws = model.forces.MakeWorkspace();
  std::mt19937 rng(2);
  std::normal_distribution<double> g;
  ReducedVector q(r), f(r);
  for (int i = 0; i < r; ++i) q[i] = 0.1 * g(rng);
  ReducedMatrix K(r, r);
  const bool with_stiffness = state.range(1) != 0;
  for (auto _ : state) {
    model.forces.Evaluate(q, &f, with_stiffness ? &K : nullptr, &ws);
    benchmark::DoNotOptimize(f.data());
    benchmark::DoNotOptimize(K.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ReducedForces)
    ->Args({15, 1})  // r = 15, force and stiffness
    ->Args({20, 0})  // r = 20, force only
    ->Args({20, 1})  // r = 20, force and stiffness
    ->Unit(benchmark::kMicrosecond);

// Deformed position and normal of embedded surface points (one haptic cycle's worth: 1000);
// the normal by the exact push-forward F^{-T} n (normal = 0) or the linear normal
// correction n + N q, renormalised (normal = 1).
void BM_EmbeddedPoints(benchmark::State& state) {
  const int r = int(state.range(0));
  const bool corrected = state.range(1) != 0;
  const ReducedModel& model = GetModel(r, ReducedModelKind::kStVK);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points, normals;
  for (int i = 0; i < 1000; ++i) {
    const int t = int(u(rng) * (model.mesh.num_tets() - 1));
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) p += 0.25 * model.mesh.vertices[model.mesh.tets[t][a]];
    points.push_back(p);
    normals.push_back(Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized());
  }
  const EmbeddedPoints embedded(model.mesh, model.basis, points, normals);
  ReducedVector q(r);
  for (int i = 0; i < r; ++i) q[i] = 0.05 * (u(rng) - 0.5);
  for (auto _ : state) {
    for (int i = 0; i < embedded.size(); ++i) {
      Eigen::Vector3d p = embedded.Position(i, q.data());
      Eigen::Vector3d n = corrected ? embedded.CorrectedNormal(i, q.data()) : embedded.Normal(i, q.data());
      benchmark::DoNotOptimize(p);
      benchmark::DoNotOptimize(n);
    }
  }
  state.SetItemsProcessed(state.iterations() * embedded.size());
}
BENCHMARK(BM_EmbeddedPoints)
    ->ArgNames({"r", "corrected"})
    ->Args({15, 0})  // r = 15, exact push-forward normal
    ->Args({15, 1})  // r = 15, linear normal correction
    ->Args({20, 0})  // r = 20, exact push-forward normal
    ->Args({20, 1})  // r = 20, linear normal correction
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace contactlab

CONTACTLAB_BENCHMARK_MAIN()
