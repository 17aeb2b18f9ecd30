// `contactlab session SCENE.yaml --device SPEC [--duration S] [--log FILE]`: a live haptic
// session (Barbič & James 2008, sec. 5). The scene's field body is the haptic body: the device
// workspace is centred on its start pose; the pointshell body stays where the scene puts it.
// A one-line status shows rate, 99th-percentile cycle time, points in contact, level
// rendered, clamps, coherence resets, contact faults (when any) and, for a device that rejects
// samples (udp), its rejection counters; the start names the device (a udp device's bound
// port); the log (CSV) replays as a recorded trajectory. A deformable body is two-way coupled
// (a bridge or a hose the user pushes with the haptic body, or the haptic body itself): its
// reduced deformation takes one step at the end of every cycle (paper sec. 4.1 and 5).
// --view [PORT] serves a live 3D view of the session on the loopback address
// (view/live_view_server.h, docs/viewer.md).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "cli/command_registry.h"
#include "experiment/contact_placement.h"
#include "experiment/scene_assets.h"
#include "experiment/scene.h"
#include "haptics/device_factory.h"
#include "haptics/haptic_cycle.h"
#include "haptics/haptic_loop.h"
#include "haptics/safety_filter.h"
#include "haptics/workspace_mapping.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"
#include "util/parse_number.h"
#include "view/display_points.h"
#include "view/live_view_server.h"
#include "view/view_data.h"
#include "view/viewer_page.h"

namespace contactlab::cli {
namespace {

struct SessionArgs {
  std::string scene;
  std::string device = "sim";
  std::string model;
  std::string log;
  std::string cache;
  double duration = 10;
  double k_vc = -1;
  double touch = -1;
  bool no_realtime = false;
  bool quiet = false;
  bool view = false;      // --view given
  std::string view_port;  // its value: a port, or empty (a free one)
};

// Columns of the session log; the first eight are the recorded-trajectory format of the
// experiment harness and the replay device (t, x, y, z, qw, qx, qy, qz of the device).
constexpr const char* kLogHeader =
    "t,x,y,z,qw,qx,qy,qz,body_x,body_y,body_z,body_qw,body_qx,body_qy,body_qz,"
    "force_x,force_y,force_z,torque_x,torque_y,torque_z,contact_fx,contact_fy,contact_fz,"
    "points_in_contact,level_rendered,nodes_visited,work_us,safety_flags,buttons,step_us,q_norm,q_norm_body\n";

void WriteRecord(std::ostream& out, const CycleRecord& r, std::int64_t t0_ns) {
  char line[720];
  std::snprintf(line, sizeof line,
                "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%lld,%.3f,%u,%u,%.3f,%.9g,%.9g\n",
                double(r.now_ns - t0_ns) * 1e-9, r.p_WD[0], r.p_WD[1], r.p_WD[2], r.q_WD[0], r.q_WD[1], r.q_WD[2],
                r.q_WD[3], r.p_WH[0], r.p_WH[1], r.p_WH[2], r.q_WH[0], r.q_WH[1], r.q_WH[2], r.q_WH[3],
                r.device_force[0], r.device_force[1], r.device_force[2], r.device_torque[0], r.device_torque[1],
                r.device_torque[2], r.contact_force[0], r.contact_force[1], r.contact_force[2], r.points_in_contact,
                r.level_rendered, static_cast<long long>(r.nodes_visited), double(r.work_ns) * 1e-3,
                r.safety_flags, r.buttons, double(r.step_ns) * 1e-3, r.q_norm, r.q_norm_B);
  out << line;
}

void RunSession(const SessionArgs& args) {
  if (!args.log.empty()) CheckOutputTarget(args.log, "--log");  // before the session, not after it
  // --view: its port and three.js, before anything is built.
  int view_port = 0;
  if (args.view) {
    if (!args.view_port.empty()) {
      const std::optional<long long> p = ParseInteger(args.view_port);
      if (!p || *p < 0 || *p > 65535) Fail("--view", QuoteToken(args.view_port) + " is not a port (0..65535; 0 or none: a free one)");
      view_port = int(*p);
    }
    RequireThreeJs();
  }
  const Scene scene = LoadScene(RequireDataFile(args.scene));
  AssetOptions options;
  options.cache_dir = args.cache;
  SceneAssets assets(scene, options);
  const std::string model_name = args.model.empty() ? scene.models.front() : args.model;
  auto model = MakeSceneContactModel(model_name, scene, assets);

  // --touch: the haptic body starts where it touches the other body, moving toward it.
  Pose X_WB_start = scene.field_body.pose;
  if (args.touch > 0) {
    const Eigen::Vector3d toward = scene.pointshell_body.pose.translation - X_WB_start.translation;
    X_WB_start = TouchAlong(scene, assets, true, scene.pointshell_body.pose, X_WB_start, toward, args.touch,
                            args.scene + ": --touch");
  }
  std::unique_ptr<HapticDevice> device = MakeDevice(args.device);
  WorkspaceMappedDevice mapped(*device, X_WB_start);
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  config.node_budget = scene.node_budget;
  // The coherence guard: the haptic body's real motion against the scene's max_point_speed.
  config.max_point_speed = scene.model.max_point_speed;
  config.cycle_seconds = scene.model.cycle_seconds;
  config.body_radius_H = assets.B.mesh()->MaxVertexRadius();
  if (args.k_vc > 0) config.coupling.k_vc = args.k_vc;
  // Deformable bodies: their dynamics step at the haptic rate, A's and the haptic body's.
  SceneDynamics dynamics = MakeSceneDynamics(assets, scene.model.cycle_seconds);
  config.dynamics_A = dynamics.A.get();
  config.dynamics_B = dynamics.B.get();
  // --view: the displayed pointshell points (the page's, same decimation) are marked with
  // their contact state by the haptic thread, a chunk per cycle.
  std::unique_ptr<ContactPointMarks> marks;
  if (args.view) {
    marks = std::make_unique<ContactPointMarks>(DecimatePointshell(*assets.A.pointshell(), SceneViewOptions{}.max_points).index);
    config.point_marks = marks.get();
  }
  HapticCycle cycle(mapped, model.get(), config);

  HapticLoopOptions loop_options;
  loop_options.duration_seconds = args.duration;
  loop_options.try_realtime = !args.no_realtime;
  InstallStopSignalHandlers();
  HapticLoop loop(cycle, loop_options);

  // The log goes to a temporary name and is renamed when the session ends cleanly; on any
  // failure the temporary is removed.
  std::ofstream log;
  std::optional<TemporaryOutput> log_output;
  if (!args.log.empty()) {
    log_output.emplace(args.log);
    log.open(log_output->temporary(), std::ios::trunc);
    if (!log) Fail(args.log, "cannot open the session log for writing");
    log << "# contactlab session log: scene " << scene.name << ", model " << model_name << ", device " << args.device
        << "\n"
        << kLogHeader;
  }

  // --view: the live view's page and server (loopback only), before the loop starts.
  std::unique_ptr<LatestValue<LiveSnapshot>> live;
  std::unique_ptr<LiveViewServer> server;
  if (args.view) {
    nlohmann::json data = SceneViewData(scene, assets, SceneViewOptions{}, BodyPoses{scene.pointshell_body.pose, X_WB_start});
    data["title"] = scene.name + " (live)";
    data["live"] = {{"stream", "stream"}, {"haptic", 1}, {"model", model_name}, {"device", args.device}};
    live = std::make_unique<LatestValue<LiveSnapshot>>();
    server = std::make_unique<LiveViewServer>(ViewerPage(data), *live, view_port, 50, marks.get());
  }

  std::string deformable;
  if (dynamics.A) deformable += ", " + scene.pointshell_body.name + " deformable, r = " + std::to_string(dynamics.A->r());
  if (dynamics.B) deformable += ", " + scene.field_body.name + " deformable, r = " + std::to_string(dynamics.B->r());
  std::printf("session: scene %s, model %s, device %s, %.1f s (Ctrl-C stops)%s\n", scene.name.c_str(),
              model_name.c_str(), args.device.c_str(), args.duration, deformable.c_str());
  // Where the device is (a udp device's bound port, also when udp:0 picked it).
  std::printf("device: %s\n", device->description().c_str());
  if (server) std::printf("view: %s\n", server->url().c_str());
  std::fflush(stdout);
  std::atomic<bool> done{false};
  std::thread consumer([&] {
    CycleRecord rec;
    std::int64_t t0 = -1, window_start = -1, window_cycles = 0;
    std::vector<double> work_us;
    work_us.reserve(4096);
    int points = 0, level = -1;
    std::uint64_t clamps = 0;
    std::int64_t coherence_resets = 0, contact_faults = 0;
    DeviceInputStats input;
    auto status = [&](std::int64_t now) {
      if (args.quiet || work_us.empty()) return;
      std::sort(work_us.begin(), work_us.end());
      const double p99 = work_us[std::min(work_us.size() - 1, std::size_t(0.99 * work_us.size()))];
      const double rate = window_cycles / std::max(1e-9, double(now - window_start) * 1e-9);
      std::fprintf(stderr, "\r%7.0f Hz  p99 %7.1f us  contacts %5d  level %2d  clamps %6llu  coherence resets %lld", rate,
                   p99, points, level, static_cast<unsigned long long>(clamps),
                   static_cast<long long>(coherence_resets));
      if (contact_faults > 0) std::fprintf(stderr, "  contact faults %lld", static_cast<long long>(contact_faults));
      // A device that rejects samples (udp): what it rejected, so zero force has a reason.
      if (input.received > 0 || input.rejected() > 0)
        std::fprintf(stderr, "  rejected %lld (malformed %lld, dup %lld, order %lld, stale %lld, future %lld) resyncs %lld",
                     static_cast<long long>(input.rejected()), static_cast<long long>(input.malformed),
                     static_cast<long long>(input.duplicate), static_cast<long long>(input.out_of_order),
                     static_cast<long long>(input.stale), static_cast<long long>(input.future),
                     static_cast<long long>(input.resyncs));
      std::fprintf(stderr, "   ");
      std::fflush(stderr);
    };
    for (;;) {
      const bool finished = done.load();
      bool popped = false;
      while (loop.records().TryPop(&rec)) {
        popped = true;
        if (t0 < 0) t0 = window_start = rec.now_ns;
        if (log.is_open()) WriteRecord(log, rec, t0);
        work_us.push_back(double(rec.work_ns) * 1e-3);
        ++window_cycles;
        points = rec.points_in_contact;
        level = rec.level_rendered;
        coherence_resets = rec.coherence_resets;
        contact_faults = rec.contact_faults;
        input = rec.device_input;
        if (rec.safety_flags & (kSafetyForceClamped | kSafetyTorqueClamped)) ++clamps;
        if (rec.now_ns - window_start > 500'000'000) {
          status(rec.now_ns);
          work_us.clear();
          window_cycles = 0;
          window_start = rec.now_ns;
        }
      }
      // The live view reads the newest record, not each one.
      if (live && popped) live->Store(SnapshotOf(rec, t0));
      if (finished) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(live ? 2 : 5));
    }
    if (!args.quiet) std::fprintf(stderr, "\n");
  });
  const HapticLoopReport report = loop.Run();
  done.store(true);
  consumer.join();
  if (server) server->Stop();
  std::printf("%s", FormatLoopReport(report).c_str());
  std::printf("  records dropped by the log consumer: %llu\n",
              static_cast<unsigned long long>(loop.records().dropped()));
  if (log.is_open()) {
    log.close();
    if (!log) Fail(args.log, "write failed (disk full or I/O error)");
    log_output->Commit();
    std::printf("session log: %s\n", args.log.c_str());
  }
}

const CommandRegistration kSessionCommands([](CLI::App& app) {
  auto args = std::make_shared<SessionArgs>();
  CLI::App* cmd = app.add_subcommand("session", "Run a live haptic session on a scene with a device at 1 kHz");
  cmd->add_option("SCENE", args->scene, "scene YAML file (its field body is the haptic body)")->required();
  cmd->add_option("--device", args->device,
                  "sim | sim:circle[:R[:PERIOD]] | replay:FILE.csv | udp:PORT[:PEER] | spacenav | plugin:LIB.so");
  cmd->add_option("--duration", args->duration, "session length, seconds")->check(CLI::PositiveNumber);
  cmd->add_option("--log", args->log, "CSV log of poses, wrenches and timings (replayable trajectory)");
  cmd->add_option("--model", args->model, "contact model (default: the scene's first)");
  cmd->add_option("--k-vc", args->k_vc, "virtual coupling stiffness, N/m")->check(CLI::PositiveNumber);
  cmd->add_option("--touch", args->touch,
                  "start the haptic body in contact: moved toward the other body until this deep, metres")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--cache", args->cache, "cache folder for fields and pointshells");
  cmd->add_flag("--no-realtime", args->no_realtime, "do not try SCHED_FIFO / mlockall");
  cmd->add_flag("--quiet", args->quiet, "no live status line");
  CLI::Option* view = cmd->add_option("--view", args->view_port,
                                      "serve a live 3D view on http://127.0.0.1:PORT/ (no PORT or 0: a free port, printed)")
                          ->expected(0, 1);
  cmd->callback([args, view] {
    args->view = view->count() > 0;
    RunSession(*args);
  });
});

}  // namespace
}  // namespace contactlab::cli
