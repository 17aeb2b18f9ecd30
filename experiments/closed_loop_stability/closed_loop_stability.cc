// Question: up to which coupling stiffness k_VC does the haptic closed loop (Barbič & James
// 2008, sec. 5: static virtual coupling, quasi-static damping alpha = 0.5, safety filter, 1 kHz)
// stay passive and settle, with each contact model on each real scene?
//
// For every scene × model × k_VC × motion (push, slide, corner; src/experiment/
// closed_loop_stability.h) it runs the sim-device loop in simulated time and records the
// energy the device put into the hand (passivity observer), the oscillation of H and of the
// device force over the first and last 200 ms of a still hold in contact, clamps and faults.
// Writes one CSV row per run (--out) and a markdown summary (--md): per model and scene the
// largest k_VC at which it and every smaller k_VC are stable for all three motions.
// Quick mode (CONTACTLAB_BENCH_QUICK=1 or --quick): one scene, two models, k_VC 1000, small
// pointshell and field, a smoke test that the program runs.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "baselines/register_baselines.h"
#include "bench_common.h"
#include "contact/model_registry.h"
#include "experiment/closed_loop_stability.h"
#include "experiment/scene.h"
#include "experiment/scene_assets.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/output_target.h"

namespace contactlab {
namespace {

struct Row {
  std::string scene, model;
  double k_vc = 0;
  LoopMotion motion = LoopMotion::kPush;
  ClosedLoopMetrics m;
};

std::string Reason(const ClosedLoopMetrics& m) { return StabilityVerdict(m); }

std::string Fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace
}  // namespace contactlab

int main(int argc, char** argv) {
  using namespace contactlab;
  CLI::App app{"Closed-loop stability of the haptic display per contact model, scene and coupling stiffness"};
  std::vector<std::string> scenes = {"knight-screwdriver", "block-joint", "dragon-bunny"};
  std::vector<std::string> models;
  std::vector<double> k_values = {400, 1000, 2000, 5000, 10000, 20000};
  std::string out = "results/closed_loop_stability.csv", md;
  std::string cache;
  int jobs = 2, points = 0, field_res = 0;
  bool quick = bench::QuickRun();
  app.add_option("--scenes", scenes, "scene names (data/scenes/NAME.yaml)");
  app.add_option("--models", models, "contact models (default: every registered model but 'reference')");
  app.add_option("--k-vc", k_values, "coupling stiffnesses, N/m")->check(CLI::PositiveNumber);
  app.add_option("--out", out, "CSV, one row per run");
  app.add_option("--md", md, "markdown summary (default: the CSV's name with .md)");
  app.add_option("--cache", cache, "asset cache folder (default: $CONTACTLAB_CACHE or ~/.cache/contactlab)");
  app.add_option("--jobs", jobs, "worker threads, one (scene, model, k_VC) at a time each")->check(CLI::Range(1, 64));
  app.add_option("--points", points, "override the pointshell body's deepest-level points (0: the scene's)")
      ->check(CLI::Range(0, 1 << 24));
  app.add_option("--field-resolution", field_res, "override both bodies' field resolution (0: the scene's)")
      ->check(CLI::Range(0, 1024));
  app.add_flag("--quick", quick, "smoke run: knight-screwdriver, pointshell and fcl, k_VC 1000, 2048 points, 64^3");
  CLI11_PARSE(app, argc, argv);
  RegisterBaselineContactModels();
  if (quick) {
    if (app.count("--scenes") == 0) scenes = {"knight-screwdriver"};
    if (app.count("--models") == 0) models = {"pointshell", "fcl"};
    if (app.count("--k-vc") == 0) k_values = {1000};
    if (points == 0) points = 2048;
    if (field_res == 0) field_res = 64;
  }
  if (models.empty()) {
    // 'reference' is the offline dense-quadrature model (seconds per query): not a haptic model.
    for (const std::string& n : ContactModelNames())
      if (n != "reference") models.push_back(n);
  }
  if (md.empty()) md = std::filesystem::path(out).replace_extension(".md").string();
  std::sort(k_values.begin(), k_values.end());

  try {
    CheckOutputTarget(out, "--out");
    CheckOutputTarget(md, "--md");
    const auto wall0 = std::chrono::steady_clock::now();
    // Assets and poses are built here, one scene at a time, with one instance of each model (the
    // assets build lazily and are not thread-safe). The runs go to the workers as one task per
    // (scene, model, k_VC), the slowest models first; a worker makes its own model instance
    // (under a lock) from the built assets.
    struct Job {
      std::string scene, model;
      Scene* spec = nullptr;
      SceneAssets* assets = nullptr;
      const ClosedLoopScene* where = nullptr;
    };
    std::vector<std::unique_ptr<Scene>> scene_store;
    std::vector<std::unique_ptr<SceneAssets>> asset_store;
    std::vector<std::unique_ptr<ClosedLoopScene>> where_store;
    std::vector<Job> jobs_list;
    AssetOptions options;
    options.cache_dir = cache;
    options.verbose = false;
    for (const std::string& name : scenes) {
      auto scene = std::make_unique<Scene>(LoadScene(RequireDataFile("scenes/" + name + ".yaml")));
      if (points > 0) {
        scene->pointshell_body.pointshell.points = points;
        scene->pointshell_body.pointshell.levels = std::min(scene->pointshell_body.pointshell.levels, 3);
      }
      if (field_res > 0) scene->pointshell_body.field.resolution = scene->field_body.field.resolution = field_res;
      auto assets = std::make_unique<SceneAssets>(*scene, options);
      std::fprintf(stderr, "closed_loop_stability: preparing %s\n", name.c_str());
      auto where = std::make_unique<ClosedLoopScene>(MakeClosedLoopScene(*scene, *assets));
      for (const std::string& model : models) {
        MakeSceneContactModel(model, *scene, *assets);  // builds what the model needs
        jobs_list.push_back({name, model, scene.get(), assets.get(), where.get()});
      }
      scene_store.push_back(std::move(scene));
      asset_store.push_back(std::move(assets));
      where_store.push_back(std::move(where));
    }
    const double prep_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

    // Tasks: (job, k index); Bullet, FCL and the tree-less pointshell are far slower per cycle, so
    // they go first.
    auto cost = [](const std::string& model) {
      return model == "bullet" ? 0 : (model == "fcl" || model == "pointshell-linear") ? 1 : model.rfind("vps", 0) == 0 ? 2 : 3;
    };
    std::vector<std::pair<std::size_t, std::size_t>> tasks;
    for (std::size_t j = 0; j < jobs_list.size(); ++j)
      for (std::size_t k = 0; k < k_values.size(); ++k) tasks.push_back({j, k});
    std::stable_sort(tasks.begin(), tasks.end(), [&](const auto& a, const auto& b) {
      return cost(jobs_list[a.first].model) < cost(jobs_list[b.first].model);
    });
    std::vector<std::vector<Row>> per_task(tasks.size());
    std::atomic<std::size_t> next{0};
    std::mutex print, make;
    auto worker = [&] {
      for (std::size_t i; (i = next.fetch_add(1)) < tasks.size();) {
        const Job& job = jobs_list[tasks[i].first];
        const double k = k_values[tasks[i].second];
        std::unique_ptr<ContactModel> instance;
        SceneDynamics dynamics;  // the deformable bodies' own, stepped by this worker's loop
        {
          std::lock_guard<std::mutex> lock(make);
          instance = MakeSceneContactModel(job.model, *job.spec, *job.assets);
          dynamics = MakeSceneDynamics(*job.assets, job.where->cycle_seconds);
        }
        for (LoopMotion motion : {LoopMotion::kPush, LoopMotion::kSlide, LoopMotion::kCorner}) {
          ClosedLoopCase c;
          c.k_vc = k;
          c.motion = motion;
          Row row{job.scene, job.model, k, motion, RunClosedLoop(*instance, *job.where, c, &dynamics)};
          {
            std::lock_guard<std::mutex> lock(print);
            std::fprintf(stderr, "%-18s %-17s k_VC %6.0f %-6s energy %+.2e J (peak %.2e) late rms %.1e m %.1e N -> %s (%.1f s)\n",
                         job.scene.c_str(), job.model.c_str(), k, LoopMotionName(motion), row.m.energy_into_hand,
                         row.m.peak_stored_energy, row.m.late_position_rms, row.m.late_force_rms,
                         Reason(row.m).c_str(), row.m.wall_seconds);
          }
          per_task[i].push_back(std::move(row));
        }
      }
    };
    std::vector<std::thread> threads;
    for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
    for (auto& t : threads) t.join();
    // Back to (scene, model) order, k_VC ascending within each.
    std::vector<std::vector<Row>> results(jobs_list.size());
    for (std::size_t j = 0; j < jobs_list.size(); ++j)
      for (std::size_t k = 0; k < k_values.size(); ++k)
        for (std::size_t i = 0; i < tasks.size(); ++i)
          if (tasks[i] == std::make_pair(j, k))
            for (Row& r : per_task[i]) results[j].push_back(std::move(r));
    const double total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

    WriteFileAtomically(out, [&](std::ostream& os) {
      os << "scene,model,k_vc,motion,energy_into_hand_J,peak_stored_energy_J,passive,early_position_rms_m,"
            "late_position_rms_m,early_force_rms_N,late_force_rms_N,hold_force_mean_N,settled,max_contact_force_N,"
            "max_device_force_N,clamped_cycles,non_finite_cycles,solve_failures,coherence_resets,contact_faults,"
            "max_points_in_contact,cycles,stable,reason,wall_s\n";
      char line[1024];
      for (const auto& rows : results) {
        for (const Row& r : rows) {
          const ClosedLoopMetrics& m = r.m;
          std::snprintf(line, sizeof line,
                        "%s,%s,%.0f,%s,%.6e,%.6e,%d,%.6e,%.6e,%.6e,%.6e,%.6e,%d,%.6g,%.6g,%lld,%lld,%lld,%lld,%lld,%d,%d,%d,%s,%.3f\n",
                        r.scene.c_str(), r.model.c_str(), r.k_vc, LoopMotionName(r.motion), m.energy_into_hand,
                        m.peak_stored_energy, int(m.passive()), m.early_position_rms, m.late_position_rms,
                        m.early_force_rms, m.late_force_rms, m.hold_force_mean, int(m.settled()), m.max_contact_force,
                        m.max_device_force, (long long)m.clamped_cycles, (long long)m.non_finite_cycles,
                        (long long)m.solve_failures, (long long)m.coherence_resets, (long long)m.contact_faults,
                        m.max_points_in_contact, m.cycles,
                        int(m.stable()), Reason(m).c_str(), m.wall_seconds);
          os << line;
        }
      }
    });

    // Markdown: verdict per k_VC (worst motion), the largest stable k_VC, and the numbers.
    std::ostringstream s;
    s << "Closed-loop stability (static virtual coupling, alpha = 0.5, 1 kHz simulated; motions push, slide, "
         "corner; " << Fmt("%.0f", total_seconds) << " s wall, " << jobs << " jobs";
    if (points > 0) s << "; pointshells " << points << " points";
    if (field_res > 0) s << "; fields " << field_res << "^3";
    s << ")\n\n| scene | model |";
    for (double k : k_values) s << " " << Fmt("%.0f", k) << " |";
    s << " largest stable k_VC |\n|---|---|";
    for (std::size_t i = 0; i < k_values.size(); ++i) s << "---|";
    s << "---|\n";
    for (const auto& rows : results) {
      if (rows.empty()) continue;
      s << "| " << rows[0].scene << " | " << rows[0].model << " |";
      double largest = 0;
      bool broken = false;
      for (double k : k_values) {
        std::string cell;
        bool all_ok = true;
        for (const Row& r : rows) {
          if (r.k_vc != k || r.m.stable()) continue;
          all_ok = false;
          cell += (cell.empty() ? "" : ", ") + Reason(r.m) + " (" + LoopMotionName(r.motion) + ")";
        }
        s << " " << (all_ok ? "ok" : cell) << " |";
        if (all_ok && !broken) largest = k;
        if (!all_ok) broken = true;
      }
      s << " " << (largest > 0 ? Fmt("%.0f", largest) : std::string("none")) << " |\n";
    }
    s << "\nNumbers per k_VC (worst motion): energy into the hand (J, > 0 = generated), the same over the peak "
         "stored coupling energy, late-hold RMS of H's position (µm) and of the device force (N), and their "
         "early-hold values; cycles with a safety clamp; mean ms per cycle.\n\n"
         "| scene | model | k_VC | energy J | energy / stored | late H µm | late F N | early H µm | early F N | "
         "clamped | ms/cycle |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& rows : results) {
      for (double k : k_values) {
        double e = -1e300, ratio = -1e300, lp = 0, lf = 0, ep = 0, ef = 0, wall = 0;
        long long clamped = 0, cycles = 0;
        std::string scene, model;
        for (const Row& r : rows) {
          if (r.k_vc != k) continue;
          scene = r.scene, model = r.model;
          e = std::max(e, r.m.energy_into_hand);
          ratio = std::max(ratio, r.m.energy_into_hand / std::max(1e-12, r.m.peak_stored_energy));
          lp = std::max(lp, r.m.late_position_rms), lf = std::max(lf, r.m.late_force_rms);
          ep = std::max(ep, r.m.early_position_rms), ef = std::max(ef, r.m.early_force_rms);
          clamped += r.m.clamped_cycles, cycles += r.m.cycles, wall += r.m.wall_seconds;
        }
        if (scene.empty()) continue;
        s << "| " << scene << " | " << model << " | " << Fmt("%.0f", k) << " | " << Fmt("%+.2e", e) << " | "
          << Fmt("%+.3f", ratio) << " | " << Fmt("%.2f", lp * 1e6) << " | " << Fmt("%.3f", lf) << " | "
          << Fmt("%.2f", ep * 1e6) << " | " << Fmt("%.3f", ef) << " | " << clamped << " | "
          << Fmt("%.3f", 1e3 * wall / std::max(1LL, cycles)) << " |\n";
      }
    }
    WriteFileAtomically(md, s.str());
    std::printf("%s", s.str().c_str());
    std::printf("closed_loop_stability: %zu runs, preparation %.1f s, total %.1f s wall; wrote %s and %s\n",
                tasks.size() * 3, prep_seconds, total_seconds, out.c_str(), md.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: closed_loop_stability: %s\n", e.what());
    return 1;
  }
}
