// `contactlab view SCENE.yaml --out F.html` and `contactlab view RESULTS_DIR [--job I] --out
// F.html`: one self-contained HTML page (three.js inlined, data embedded; docs/viewer.md) that
// shows a scene's two bodies at their start poses with the pointshell body's points coloured by
// level and a slice of the field body's distance field (Barbič & James 2008, sec. 2.2-2.4), or
// replays an experiment's run: per-cycle poses and forces of each model, a time slider and a
// force plot; of a results folder with several jobs (a sweep) every job, with a job selector,
// unless --job picks one.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/command_registry.h"
#include "contact/model_registry.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"
#include "util/parse_number.h"
#include "view/view_data.h"
#include "view/viewer_page.h"

namespace contactlab::cli {
namespace {

namespace fs = std::filesystem;

// Where DATA (the page's embedded data) holds a non-finite number, which JSON cannot spell (the
// page would show nothing there): true with *WHERE its key path and *VALUE the number.
bool FindNonFinite(const nlohmann::json& data, std::string* where, double* value) {
  if (data.is_number_float()) {
    *value = data.get<double>();
    return !std::isfinite(*value);
  }
  if (data.is_object()) {
    for (const auto& [key, item] : data.items()) {
      if (FindNonFinite(item, where, value)) return where->insert(0, "." + key), true;
    }
  } else if (data.is_array()) {
    for (std::size_t i = 0; i < data.size(); ++i) {
      if (FindNonFinite(data[i], where, value)) return where->insert(0, "[" + std::to_string(i) + "]"), true;
    }
  }
  return false;
}

// Throws Error naming FILE when DATA holds a non-finite number.
void RequireFiniteViewData(const nlohmann::json& data, const std::string& file) {
  std::string where;
  double value = 0;
  if (FindNonFinite(data, &where, &value)) {
    Fail(file, "cannot write the page: data" + where + " is " + std::to_string(value) +
                   ", not a finite number; nothing written");
  }
}

struct ViewArgs {
  std::string input;
  std::string out;
  std::optional<int> job;  // --job, when given
  int max_points = 50000;
  int max_triangles = 50000;
  int max_frames = 10000;
  int max_surface_frames = 200;
  std::vector<std::string> models;  // --model: the scene's models to draw the contact surface of
  std::string slice_axis = "auto";
  std::string slice_at;  // empty: automatic
  std::string cache;
  bool no_cache = false;
};

void RunView(const ViewArgs& args) {
  CheckOutputWritable(args.out, "--out");
  RequireThreeJs();
  if (args.job && *args.job < 0) Fail("--job", std::to_string(*args.job) + " is not a job index (jobs count from 0)");
  if (args.max_points < 16) Fail("--max-points", "must be at least 16, got " + std::to_string(args.max_points));
  SceneViewOptions options;
  options.max_points = args.max_points;
  if (args.max_triangles != 0 && args.max_triangles < 4) {
    Fail("--max-triangles", "must be at least 4 (or 0: every triangle), got " + std::to_string(args.max_triangles));
  }
  options.max_triangles = args.max_triangles;
  if (args.max_surface_frames < 0) {
    Fail("--max-surface-frames", "must be at least 0, got " + std::to_string(args.max_surface_frames));
  }
  options.max_surface_frames = args.max_surface_frames;
  options.slice_axis = args.slice_axis == "auto" ? -1 : args.slice_axis == "x" ? 0 : args.slice_axis == "y" ? 1 : 2;
  if (!args.slice_at.empty()) {
    const std::optional<double> at = ParseDouble(args.slice_at);
    if (!at) Fail("--slice-at", "'" + QuoteToken(args.slice_at) + "' is not a finite number (metres)");
    options.slice_at = *at;
  }
  AssetOptions assets_options;
  assets_options.cache_dir = args.cache;
  assets_options.use_cache = !args.no_cache;

  nlohmann::json data;
  std::string what;
  if (fs::is_directory(args.input)) {
    // A results folder: replay one job.
    for (const fs::directory_entry& e : fs::directory_iterator(args.input)) {
      if (e.is_regular_file()) CheckOutputIsNotInput(args.out, e.path(), "--out");
    }
    // A job's page: of two bodies, or of a scene of many (study: many-bodies).
    auto job_view = [&](const Replay& replay) {
      if (replay.scene.many_bodies()) return WorldReplayViewData(replay, assets_options, options);
      SceneAssets assets(replay.scene, assets_options);
      return ReplayViewData(replay, assets, options);
    };
    if (args.job) {
      const Replay replay = ReadReplay(args.input, args.job, args.max_frames);
      data = job_view(replay);
      what = "replay of " + args.input + ", job " + std::to_string(replay.job) + ", " +
             std::to_string(replay.tracks.size()) + " model(s)";
    } else {
      // Without --job: every job the folder holds, the first shown, a selector for the others.
      const std::vector<Replay> replays = ReadReplays(args.input, args.max_frames);
      std::vector<nlohmann::json> job_data;
      for (const Replay& replay : replays) job_data.push_back(job_view(replay));
      if (replays.size() == 1) {
        data = std::move(job_data.front());
        what = "replay of " + args.input + ", job " + std::to_string(replays.front().job) + ", " +
               std::to_string(replays.front().tracks.size()) + " model(s)";
      } else {
        data = SeveralJobsViewData(replays, std::move(job_data));
        what = "replay of " + args.input + ", " + std::to_string(replays.size()) + " jobs (job " +
               std::to_string(replays.front().job) + " shown first, the others by the page's job selector)";
      }
    }
  } else {
    // A scene file.
    if (args.job) Fail("--job", "applies to a results folder, not to the scene " + args.input);
    if (!args.models.empty()) {
      for (const std::string& m : args.models) {
        if (FindContactModel(m) == nullptr) {
          std::string known;
          for (const std::string& n : ContactModelNames()) known += (known.empty() ? "" : ", ") + n;
          Fail("--model", "unknown contact model '" + QuoteToken(m) + "' (known: " + known + ")");
        }
      }
    }
    const fs::path scene_file = RequireDataFile(args.input);
    CheckOutputIsNotInput(args.out, scene_file, "--out");
    Scene scene = LoadScene(scene_file);
    if (!args.models.empty()) scene.models = args.models;
    for (const BodySpec* b : scene.AllBodies()) {
      if (const auto mesh_file = FindDataFile(b->mesh, FolderOf(scene_file))) CheckOutputIsNotInput(args.out, *mesh_file, "--out");
    }
    if (scene.many_bodies()) {
      // Every body's mesh and the pairs; a pair's pointshell and field are not built for the page.
      data = ManyBodiesViewData(scene, scene.models.front(), assets_options, options);
      what = "scene " + scene.name + ", " + std::to_string(scene.bodies.size()) + " bodies, tool " +
             scene.bodies[std::size_t(scene.tool)].name + ", " + std::to_string(scene.pairs.size()) + " pairs";
    } else {
      SceneAssets assets(scene, assets_options);
      data = SceneViewData(scene, assets, options);
      what = "scene " + scene.name;
    }
  }
  RequireFiniteViewData(data, args.out);
  const std::string page = ViewerPage(data);
  WriteFileAtomically(args.out, page);
  std::fprintf(stderr, "%s: %s, %.1f MB\n", args.out.c_str(), what.c_str(), double(page.size()) / 1e6);
}

const CommandRegistration kView([](CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Write a self-contained HTML page with a 3D view: of a scene (bodies at their start poses, the "
              "pointshell by level, a slice of the distance field) or of a results folder (a replay of its jobs: "
              "poses, forces, time slider, force plot, job selector)");
  cmd->add_option("INPUT", args->input, "scene YAML file, or a results folder of `contactlab run`")->required();
  cmd->add_option("--out", args->out, "the HTML file to write")->required();
  cmd->add_option("--job", args->job, "results folder: the only job to replay (default: every job, the first shown, a job selector in the page)");
  cmd->add_option("--max-points", args->max_points, "pointshell points drawn at most, split over the levels (default 50000)");
  cmd->add_option("--max-triangles", args->max_triangles,
                  "triangles drawn per body at most, larger meshes thinned by edge collapse (default 50000; 0: all)");
  cmd->add_option("--max-frames", args->max_frames, "replay: frames per model at most, every k-th cycle kept (default 10000)");
  cmd->add_option("--max-surface-frames", args->max_surface_frames,
                  "replay: frames per model whose contact surface (pressure-field) is drawn, evenly spaced "
                  "(default 200; 0: none)");
  cmd->add_option("--model", args->models,
                  "scene: draw the contact surface of this model at the start poses (pressure-field; repeatable; "
                  "default: the scene's models)");
  cmd->add_option("--slice-axis", args->slice_axis, "normal of the field slice in the field body's frame (default: auto)")
      ->check(CLI::IsMember({"auto", "x", "y", "z"}));
  cmd->add_option("--slice-at", args->slice_at, "the slice's coordinate along its axis, field body frame, metres "
                                                "(default: through the pointshell body's origin)");
  cmd->add_option("--cache", args->cache, "cache folder for fields and pointshells");
  cmd->add_flag("--no-cache", args->no_cache, "neither read nor write cached fields and pointshells");
  cmd->callback([args] { RunView(*args); });
});

}  // namespace
}  // namespace contactlab::cli
