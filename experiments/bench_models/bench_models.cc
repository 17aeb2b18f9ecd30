// Question: what does one query of each registered contact model cost — the paper's
// pointshell models (Barbič & James 2008, sec. 2.1, 3), VPS, FCL, Bullet and the offline
// eq. (2) reference — on the same real mesh pairs in shallow (0.5 mm) and deep (2 mm)
// contact, and how far is each model's force direction from the model-independent reference
// (-∇V, the CGAL overlap-volume gradient of baselines/reference)?
//
// Placement as in bench_contact: A moves from its scene pose toward B's origin until the
// pointshell-linear model sees the target depth plus the pointshell's offset (so the meshes
// themselves overlap by about the target depth; without it the "shallow" meshes do not touch). The reference direction is computed once
// per configuration, outside the timed loop: -∇V when CGAL can corefine the two meshes, else
// the direction of the dense-quadrature eq. (2) limit (counter ref_kind = 1 or 2; 0 = none).
// Counters: contacts (points or contacts contributing), dir_err_deg, force_N, ref_kind.
// Moving contact (moving/): per-cycle percentiles while A slides through the deep configuration.
// Deep press (deep/): A leaned 20 mm into B and back, without and with each real-time model's
// time budget (its node_budget unit): does the budget keep the cycle's p99.9 within 1 ms?
// Quick mode (CONTACTLAB_BENCH_QUICK=1): the procedural sphere-on-plate scene only.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "contact/register_contact_models.h"
#include "bench_common.h"
#include "bench_main.h"
#include "placed_scene.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "scene/contact_placement.h"
#include "scene/scene_assets.h"
#include "scene/scene.h"
#include "scene/scene_world.h"
#include "clutter_scene.h"
#include "util/data_path.h"
#include "util/error.h"
#ifdef CONTACTLAB_HAVE_CGAL
#include "baselines/reference/penetration_volume.h"
#include "baselines/reference/surface_quadrature_reference.h"
#endif

namespace contactlab {
namespace {

using bench::kDepthNames;

struct Configuration {
  Pose X_WA, X_WB;
  bool placed = false;
  Eigen::Vector3d reference_direction = Eigen::Vector3d::Zero();  // unit, or zero if none
  int reference_kind = 0;  // 1: -grad V (CGAL corefinement), 2: eq. (2) quadrature limit, 0: none
};

struct Prepared {
  Scene scene;
  SceneAssets* assets = nullptr;  // owned by the PlacedScene cache
  Configuration config[2];
  std::map<std::string, std::unique_ptr<ContactModel>> models;  // made once, outside timing
  std::map<std::string, std::string> model_errors;
};

// The reference direction of the force on B at one configuration (see the file comment).
void ComputeReference(Prepared& p, Configuration& c) {
#ifdef CONTACTLAB_HAVE_CGAL
  try {
    const PenetrationVolume volume(*p.assets->A.mesh(), *p.assets->B.mesh());
    const Vector6d g = volume.Gradient(c.X_WA, c.X_WB, 1e-4, 1e-3, /*with_rotation=*/false);
    if (g.head<3>().norm() > 0) {
      c.reference_direction = -g.head<3>().normalized();
      c.reference_kind = 1;
      return;
    }
  } catch (const Error& e) {
    std::cerr << p.scene.name << ": no volume gradient (" << e.what() << "); using the quadrature limit\n";
  }
  try {
    QuadratureReferenceParams params;
    params.penalty = p.scene.model.penalty;
    if (params.penalty.L <= 0) params.penalty.L = PenaltyParams::kDefaultManyPointThreshold;
    const QuadratureReference reference(p.assets->A.mesh(), p.assets->B.mesh(), params);
    const Eigen::Vector3d F = reference.Limit(c.X_WA, c.X_WB).on_B.force;
    if (F.norm() > 0) {
      c.reference_direction = F.normalized();
      c.reference_kind = 2;
    }
  } catch (const Error& e) {
    std::cerr << p.scene.name << ": no quadrature reference either (" << e.what() << ")\n";
  }
#endif
}

Prepared& Prepare(const std::string& scene_file) {
  static std::map<std::string, Prepared> cache;
  auto it = cache.find(scene_file);
  if (it != cache.end()) return it->second;
  Prepared& p = cache[scene_file];
  // The pointshell sits on A's offset surface (offset δ outside the mesh), so the mesh-based
  // models (FCL, Bullet, the references) see the meshes overlap by (pointshell depth - δ):
  // the placement aims at kDepths + δ so the meshes themselves overlap by about kDepths.
  bench::PlacedScene& placed = bench::PreparePlacedScene(scene_file, 0, 0, /*add_offset=*/true);
  p.scene = placed.scene;
  p.assets = placed.assets.get();
  for (int d = 0; d < 2; ++d) {
    p.config[d].X_WA = placed.X_WA[d];
    p.config[d].X_WB = placed.X_WB;
    p.config[d].placed = placed.placed[d];
    if (placed.placed[d]) ComputeReference(p, p.config[d]);
  }
  return p;
}

// The friction of the "+friction" rows (contact/friction.h): what moving/ costs with it on.
constexpr const char* kFriction = "{friction: {static: 0.5, dynamic: 0.4, stiffness: 2000}}";

ContactModel* GetModel(Prepared& p, const std::string& name, std::string* error) {
  auto it = p.models.find(name);
  if (it != p.models.end()) return it->second.get();
  auto e = p.model_errors.find(name);
  if (e != p.model_errors.end()) {
    *error = e->second;
    return nullptr;
  }
  try {
    // "MODEL@KEY=VALUE": the model with that key of the scene's model section (e.g. its own
    // pressure_lattice), read as a scene file reads it; "MODEL+friction": with kFriction.
    Scene scene = p.scene;
    std::string model = name;
    if (const auto plus = name.find("+friction"); plus != std::string::npos) {
      model = name.substr(0, plus);
      scene = WithModelSection(scene, ConfigNode::LoadString(kFriction, name));
    } else if (const auto at = name.find('@'); at != std::string::npos) {
      model = name.substr(0, at);
      std::string key_value = name.substr(at + 1);
      key_value.replace(key_value.find('='), 1, ": ");
      scene = WithModelSection(scene, ConfigNode::LoadString("{" + key_value + "}", name));
    }
    return (p.models[name] = MakeSceneContactModel(model, scene, *p.assets)).get();
  } catch (const Error& err) {
    p.models.erase(name);
    *error = p.model_errors[name] = err.what();
    return nullptr;
  }
}

// The model MODEL_NAME of SCENE_FILE's prepared scene and its configuration DEPTH, or null with
// STATE skipped (the bodies could not be placed, or the model refused the scene).
ContactModel* PreparedModel(benchmark::State& state, const std::string& scene_file, const std::string& model_name,
                            int depth, const Configuration** config) {
  Prepared& p = Prepare(scene_file);
  *config = &p.config[depth];
  if (!(*config)->placed) {
    state.SkipWithError("could not place the bodies in contact");
    return nullptr;
  }
  std::string error;
  ContactModel* model = GetModel(p, model_name, &error);
  if (!model) state.SkipWithError(error.c_str());
  return model;
}

void BM_ModelQuery(benchmark::State& state, std::string scene_file, std::string model_name, int depth) {
  const Configuration* config = nullptr;
  ContactModel* model = PreparedModel(state, scene_file, model_name, depth, &config);
  if (!model) return;
  const Configuration& c = *config;
  ContactQuery q;
  q.X_WA = c.X_WA;
  q.X_WB = c.X_WB;
  model->Reset();
  ContactResult r;
  std::int64_t cycles = 0;
  for (auto _ : state) {
    q.cycle = cycles++;
    r = model->Evaluate(q);
    benchmark::DoNotOptimize(r);
  }
  state.counters["contacts"] = r.stats.points_in_contact;
  state.counters["force_N"] = r.on_B.force.norm();
  state.counters["ref_kind"] = c.reference_kind;
  double err = NAN;
  if (c.reference_kind != 0) {
    err = r.on_B.force.norm() > 0
              ? std::acos(std::clamp(r.on_B.force.normalized().dot(c.reference_direction), -1.0, 1.0)) * 180 / M_PI
              : 180.0;
  }
  state.counters["dir_err_deg"] = err;
  state.SetItemsProcessed(cycles);
}

// Triangle wave through 0 between -AMPLITUDE and +AMPLITUDE, STEP per cycle: the offset at K.
double Triangle(std::int64_t k, double step, double amplitude) {
  const double period = 4 * amplitude;
  double u = std::fmod(double(k) * step + amplitude, period);  // 0 at -amplitude
  return u < 2 * amplitude ? u - amplitude : 3 * amplitude - u;
}

// MODEL's answer to Q, its wall time in microseconds in *MICROSECONDS.
ContactResult TimedQuery(ContactModel* model, const ContactQuery& q, double* microseconds) {
  const auto t0 = std::chrono::steady_clock::now();
  const ContactResult r = model->Evaluate(q);
  const auto t1 = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(r);
  *microseconds = std::chrono::duration<double, std::micro>(t1 - t0).count();
  return r;
}

// Counters p50_us, p99_us, p999_us from TIMES, a ring of per-cycle microseconds of which the
// latest CYCLES (at most its size) are filled.
void SetCycleTimeCounters(benchmark::State& state, std::vector<double>* times, std::int64_t cycles) {
  times->resize(std::min<std::size_t>(times->size(), std::size_t(cycles)));
  std::sort(times->begin(), times->end());
  auto quantile = [&](double f) {
    return times->empty() ? NAN : (*times)[std::size_t(f * double(times->size() - 1))];
  };
  state.counters["p50_us"] = quantile(0.5);
  state.counters["p99_us"] = quantile(0.99);
  state.counters["p999_us"] = quantile(0.999);
}

// One query per cycle while A slides back and forth across B at SPEED (m/s at 1 kHz) through the
// deep (2 mm) configuration, 2 cm either side, along a direction perpendicular to the line of
// the bodies' origins: the cost of a moving contact, where coherence and a proxy's sliding do
// their work. Counters p50_us, p99_us, p999_us: per-cycle times measured around each query.
void BM_ModelAtSpeed(benchmark::State& state, std::string scene_file, std::string model_name, double speed) {
  const Configuration* config = nullptr;
  ContactModel* model = PreparedModel(state, scene_file, model_name, 1, &config);
  if (!model) return;
  const Configuration& c = *config;
  const Eigen::Vector3d n = (c.X_WB.translation - c.X_WA.translation).normalized();
  const Eigen::Vector3d tangent = n.unitOrthogonal();
  constexpr std::size_t kKept = 1 << 16;
  std::vector<double> times(kKept);  // per-cycle microseconds, a ring of the latest
  ContactQuery q;
  q.X_WB = c.X_WB;
  model->Reset();
  std::int64_t cycles = 0;
  std::int64_t contacts = 0;
  for (auto _ : state) {
    q.X_WA = c.X_WA;
    q.X_WA.translation += Triangle(cycles, speed * 1e-3, 0.02) * tangent;
    q.cycle = cycles;
    const ContactResult r = TimedQuery(model, q, &times[std::size_t(cycles) % kKept]);
    contacts += r.stats.points_in_contact;
    ++cycles;
  }
  SetCycleTimeCounters(state, &times, cycles);
  state.counters["contacts"] = cycles > 0 ? double(contacts) / double(cycles) : 0;
  state.SetItemsProcessed(cycles);
}

// A user leaning on the device: A pressed from the deep (2 mm) configuration along the line of
// the bodies' origins to 20 mm past first contact and back, 0.1 mm a cycle (0.1 m/s at 1 kHz),
// with the query's node budget BUDGET (each model's own unit, ContactStats::degraded; 0: none).
// Counters p50_us, p99_us, p999_us: per-cycle times; degraded: the share of cycles the budget
// made the model degrade; force_N: the largest |F|.
void BM_ModelDeepPress(benchmark::State& state, std::string scene_file, std::string model_name, std::int64_t budget) {
  const Configuration* config = nullptr;
  ContactModel* model = PreparedModel(state, scene_file, model_name, 1, &config);
  if (!model) return;
  const Configuration& c = *config;
  const Eigen::Vector3d n = (c.X_WB.translation - c.X_WA.translation).normalized();
  constexpr double kStep = 1e-4, kDepth = 0.018;  // metres a cycle, and past the deep configuration
  constexpr std::size_t kKept = 1 << 16;
  std::vector<double> times(kKept);
  ContactQuery q;
  q.X_WB = c.X_WB;
  q.node_budget = budget;
  model->Reset();
  std::int64_t cycles = 0, degraded = 0;
  double largest = 0;
  for (auto _ : state) {
    q.X_WA = c.X_WA;
    q.X_WA.translation += (Triangle(cycles, kStep, 0.5 * kDepth) + 0.5 * kDepth) * n;
    q.cycle = cycles;
    const ContactResult r = TimedQuery(model, q, &times[std::size_t(cycles) % kKept]);
    degraded += r.stats.degraded > 0;
    largest = std::max(largest, r.on_B.force.norm());
    ++cycles;
  }
  SetCycleTimeCounters(state, &times, cycles);
  state.counters["degraded"] = cycles > 0 ? double(degraded) / double(cycles) : 0;
  state.counters["force_N"] = largest;
  state.SetItemsProcessed(cycles);
}

// The world of the cluttered scene of BODIES bodies with MODEL between the tool and each body,
// made once (its bodies' data through the cache), or null with *ERROR.
SceneWorld* ClutterWorld(int bodies, const std::string& model, std::string* error) {
  static std::map<std::pair<int, std::string>, std::unique_ptr<SceneWorld>> worlds;
  static std::map<std::pair<int, std::string>, std::string> errors;
  const auto key = std::make_pair(bodies, model);
  if (auto it = worlds.find(key); it != worlds.end()) return it->second.get();
  if (auto it = errors.find(key); it != errors.end()) {
    *error = it->second;
    return nullptr;
  }
  try {
    const std::string name = "clutter-" + std::to_string(bodies) + ".yaml";
    const Scene scene = ParseScene(ConfigNode::LoadString(bench::ClutterSceneYaml(bodies), name));
    AssetOptions options;
    options.verbose = false;
    return (worlds[key] = std::make_unique<SceneWorld>(scene, model, options)).get();
  } catch (const Error& e) {
    *error = errors[key] = e.what();
    return nullptr;
  }
}

// The tool of the cluttered scene sliding 2 cm either way along the wall at 1 m/s (1 mm a cycle
// at 1 kHz), touching the floor and the wall throughout: one cycle over every pair per iteration.
// Counters p50_us, p99_us, p999_us (per-cycle times), near (pairs near, mean), touching (mean),
// contacts (points in contact, mean).
void BM_Clutter(benchmark::State& state, int bodies, std::string model_name) {
  std::string error;
  SceneWorld* world = ClutterWorld(bodies, model_name, &error);
  if (world == nullptr) {
    state.SkipWithError(error.c_str());
    return;
  }
  const Pose start = world->scene().bodies[std::size_t(world->tool())].pose;
  constexpr std::size_t kKept = 1 << 16;
  std::vector<double> times(kKept);
  world->Reset();
  std::int64_t cycles = 0, near = 0, touching = 0, contacts = 0;
  for (auto _ : state) {
    Pose X = start;
    X.translation.y() += Triangle(cycles, 1e-3, 0.02);
    const auto t0 = std::chrono::steady_clock::now();
    const WorldResult& r = world->Evaluate(X, cycles);
    const auto t1 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(r);
    times[std::size_t(cycles) % kKept] = std::chrono::duration<double, std::micro>(t1 - t0).count();
    near += r.stats.pairs_near;
    touching += r.stats.pairs_touching;
    contacts += r.stats.sum.points_in_contact;
    ++cycles;
  }
  SetCycleTimeCounters(state, &times, cycles);
  const double n = double(std::max<std::int64_t>(1, cycles));
  state.counters["near"] = double(near) / n;
  state.counters["touching"] = double(touching) / n;
  state.counters["contacts"] = double(contacts) / n;
  state.SetItemsProcessed(cycles);
}

// The broad phase and pair bookkeeping alone on the same motion (SceneWorld::FindNearPairs):
// counters p50_us, p99_us, p999_us per cycle.
void BM_ClutterBroadPhase(benchmark::State& state, int bodies) {
  std::string error;
  SceneWorld* world = ClutterWorld(bodies, "pointshell", &error);
  if (world == nullptr) {
    state.SkipWithError(error.c_str());
    return;
  }
  const Pose start = world->scene().bodies[std::size_t(world->tool())].pose;
  constexpr std::size_t kKept = 1 << 16;
  std::vector<double> times(kKept);
  world->Reset();
  std::int64_t cycles = 0;
  for (auto _ : state) {
    Pose X = start;
    X.translation.y() += Triangle(cycles, 1e-3, 0.02);
    const auto t0 = std::chrono::steady_clock::now();
    world->FindNearPairs(X);
    const auto t1 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(world->near_pairs().data());
    times[std::size_t(cycles) % kKept] = std::chrono::duration<double, std::micro>(t1 - t0).count();
    ++cycles;
  }
  SetCycleTimeCounters(state, &times, cycles);
  state.counters["near"] = double(world->near_pairs().size());
  state.SetItemsProcessed(cycles);
}

// The budget each real-time model gets in the deep press (its own unit, ContactStats::degraded):
// the paper's model tree nodes, pointshell-ccd lookups, inner-spheres sphere pairs, pressure-field
// lattice cells, vps points looked at.
constexpr std::pair<const char*, std::int64_t> kDeepBudgets[] = {
    {"pointshell", 3000}, {"pointshell-ccd", 3000}, {"inner-spheres", 3000},
    {"pressure-field", 1000}, {"vps", 5000}, {"vps-repulsion", 5000}};

void RegisterAll() {
  RegisterContactModels();
  // Clutter: cost against the number of bodies at two contacts, per real-time model.
  const std::vector<int> clutter = bench::QuickRun() ? std::vector<int>{3, 65} : std::vector<int>{3, 9, 65, 257};
  const std::vector<std::string> clutter_models =
      bench::QuickRun() ? std::vector<std::string>{"pointshell", "fcl"}
                        : std::vector<std::string>{"pointshell", "pointshell-ccd", "vps", "pressure-field",
                                                   "inner-spheres", "fcl", "bullet"};
  for (const int bodies : clutter) {
    for (const std::string& model : clutter_models) {
      const std::string name = "clutter/" + std::to_string(bodies) + "/" + model;
      benchmark::RegisterBenchmark(name.c_str(), BM_Clutter, bodies, model)->Unit(benchmark::kMicrosecond);
    }
    const std::string name = "clutter/" + std::to_string(bodies) + "/broad-phase";
    benchmark::RegisterBenchmark(name.c_str(), BM_ClutterBroadPhase, bodies)->Unit(benchmark::kMicrosecond);
  }
  std::vector<std::string> scenes;
  if (bench::QuickRun()) {
    scenes = {"scenes/sphere-on-plate.yaml"};
  } else {
    scenes = {"scenes/dragon-bunny.yaml", "scenes/knight-screwdriver.yaml", "scenes/block-joint.yaml",
              "scenes/bumpy-cube-plate.yaml"};
  }
  for (const std::string& scene : scenes) {
    for (const std::string& model : ContactModelNames()) {
      for (int depth = 0; depth < 2; ++depth) {
        const std::string name =
            "model/" + std::filesystem::path(scene).stem().string() + "/" + model + "/" + kDepthNames[depth];
        // One query per iteration; offline models (reference) run a few iterations only.
        auto* b = benchmark::RegisterBenchmark(name.c_str(), BM_ModelQuery, scene, model, depth)
                      ->Unit(benchmark::kMicrosecond);
        if (model == "reference") b->Iterations(bench::QuickRun() ? 1 : 3);
      }
    }
    // Moving contact: the paper's model against the proxy of pointshell-ccd at 1 and 20 m/s, and
    // against the volumetric models, FCL and Bullet on the same poses at 1 m/s (per-cycle
    // percentiles: the 1 kHz budget is the p99.9).
    // The pressure field also on a coarser lattice (every 2nd and 4th grid line): what its
    // speed costs in accuracy (dir_err_deg, force_N of the model/ runs).
    for (const std::string& model : {"pressure-field@pressure_lattice=2", "pressure-field@pressure_lattice=4"}) {
      for (int depth = 0; depth < 2; ++depth) {
        const std::string name =
            "model/" + std::filesystem::path(scene).stem().string() + "/" + model + "/" + kDepthNames[depth];
        benchmark::RegisterBenchmark(name.c_str(), BM_ModelQuery, scene, model, depth)->Unit(benchmark::kMicrosecond);
      }
    }
    for (const std::string& model :
         {"pointshell", "pointshell-ccd", "pressure-field", "pressure-field@pressure_lattice=2",
          "pressure-field@pressure_lattice=4", "inner-spheres", "vps", "fcl", "bullet"}) {
      const bool proxy_pair = model == "pointshell" || model == "pointshell-ccd";
      for (const double speed : {1.0, 20.0}) {
        if (speed > 1 && !proxy_pair) continue;
        const std::string name = "moving/" + std::filesystem::path(scene).stem().string() + "/" + model + "/" +
                                 (speed == 1.0 ? "1m_s" : "20m_s");
        benchmark::RegisterBenchmark(name.c_str(), BM_ModelAtSpeed, scene, model, speed)->Unit(benchmark::kMicrosecond);
      }
    }
    // The same moving contact with friction on, for the models that carry it: friction's cost
    // as a ratio to the row above in one run.
    for (const char* model : {"pointshell", "vps", "fcl", "bullet"}) {
      const std::string name = "moving/" + std::filesystem::path(scene).stem().string() + "/" + model + "+friction/1m_s";
      benchmark::RegisterBenchmark(name.c_str(), BM_ModelAtSpeed, scene, std::string(model) + "+friction", 1.0)
          ->Unit(benchmark::kMicrosecond);
    }
    // Deep press, unbudgeted and with each model's budget; FCL and Bullet have none.
    const std::string stem = std::filesystem::path(scene).stem().string();
    for (const auto& [model, budget] : kDeepBudgets) {
      for (const std::int64_t b : {std::int64_t(0), budget}) {
        const std::string name = "deep/" + stem + "/" + model + "/budget_" + std::to_string(b);
        benchmark::RegisterBenchmark(name.c_str(), BM_ModelDeepPress, scene, std::string(model), b)
            ->Unit(benchmark::kMicrosecond);
      }
    }
    for (const char* model : {"fcl", "bullet"}) {
      const std::string name = "deep/" + stem + "/" + model + "/budget_0";
      benchmark::RegisterBenchmark(name.c_str(), BM_ModelDeepPress, scene, std::string(model), std::int64_t(0))
          ->Unit(benchmark::kMicrosecond);
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
