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
// (view/live_view_server.h, docs/viewer.md); with --view-wait [N] the session starts once N
// viewers opened the view's stream. The report splits deadline misses into overrun and
// preempted and lists the largest ten; the log carries each cycle's CPU time (cpu_us).
// --cpu N pins the loop thread to core N and keeps every other thread of the session off it
// (docs/sessions.md). The loop runs at the scene's rate, 1 / model.cycle_seconds (1 kHz by
// default); --rate HZ sets the scene's cycle to 1 / HZ, so that the loop, the contact model's
// coherence and the deformable bodies' steps all count in the same cycle.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "cli/command_registry.h"
#include "scene/contact_placement.h"
#include "scene/scene_assets.h"
#include "scene/scene.h"
#include "scene/scene_query.h"
#include "scene/scene_world.h"
#include "haptics/cpu_affinity.h"
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
  std::vector<std::string> device_peers;  // --device-peer: senders a udp device off the loopback accepts
  std::string model;
  std::string log;
  std::string cache;
  double duration = 10;
  double rate = -1;  // --rate: the loop's rate, Hz (sets model.cycle_seconds); <= 0: the scene's
  long long budget = -1;  // --budget: the node budget (sets the scene's node_budget); < 0: the scene's
  double k_vc = -1;
  double touch = -1;
  bool no_realtime = false;
  bool quiet = false;
  bool view = false;      // --view given
  std::string view_port;  // its value: a port, or empty (a free one)
  bool view_wait = false;       // --view-wait given
  std::string view_wait_count;  // its value: how many viewers, or empty (one)
  bool cpu_given = false;       // --cpu given
  std::string cpu;              // its value: the loop thread's core
};

// Columns of the session log; the first eight are the recorded-trajectory format of the
// experiment harness and the replay device (t, x, y, z, qw, qx, qy, qz of the device).
constexpr const char* kLogHeader =
    "t,x,y,z,qw,qx,qy,qz,body_x,body_y,body_z,body_qw,body_qx,body_qy,body_qz,"
    "force_x,force_y,force_z,torque_x,torque_y,torque_z,contact_fx,contact_fy,contact_fz,"
    "points_in_contact,level_rendered,nodes_visited,work_us,safety_flags,buttons,step_us,q_norm,q_norm_body,cpu_us\n";

void WriteRecord(std::ostream& out, const CycleRecord& r, std::int64_t t0_ns) {
  char line[760];
  std::snprintf(line, sizeof line,
                "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%lld,%.3f,%u,%u,%.3f,%.9g,%.9g,%.3f\n",
                double(r.now_ns - t0_ns) * 1e-9, r.p_WD[0], r.p_WD[1], r.p_WD[2], r.q_WD[0], r.q_WD[1], r.q_WD[2],
                r.q_WD[3], r.p_WH[0], r.p_WH[1], r.p_WH[2], r.q_WH[0], r.q_WH[1], r.q_WH[2], r.q_WH[3],
                r.device_force[0], r.device_force[1], r.device_force[2], r.device_torque[0], r.device_torque[1],
                r.device_torque[2], r.contact_force[0], r.contact_force[1], r.contact_force[2], r.points_in_contact,
                r.level_rendered, static_cast<long long>(r.nodes_visited), double(r.work_ns) * 1e-3,
                r.safety_flags, r.buttons, double(r.step_ns) * 1e-3, r.q_norm, r.q_norm_B, double(r.cpu_ns) * 1e-3);
  out << line;
}

// The options checked before anything is built: the live view's and the loop's core.
struct CheckedOptions {
  int port = 0;     // --view's port (0: a free one)
  int viewers = 0;  // --view-wait: the streams to wait for before the session starts (0: none)
  int cpu = -1;     // --cpu: the loop thread's core (-1: not pinned)
};

// --cpu, the log's target, --view's port and three.js, and --view-wait, checked before
// anything is built.
CheckedOptions CheckSessionOptions(const SessionArgs& args) {
  CheckedOptions checked;
  if (args.cpu_given) checked.cpu = ParseLoopCpu(args.cpu, "--cpu");
  if (!args.log.empty()) CheckOutputWritable(args.log, "--log");  // before the session, not after it
  if (args.view_wait) {
    if (!args.view) Fail("--view-wait", "needs --view");
    checked.viewers = 1;
    if (!args.view_wait_count.empty()) {
      const std::optional<long long> n = ParseInteger(args.view_wait_count);
      if (!n || *n < 1 || *n > 64) Fail("--view-wait", QuoteToken(args.view_wait_count) + " is not a number of viewers (1..64)");
      checked.viewers = int(*n);
    }
  }
  if (!args.view) return checked;
  if (!args.view_port.empty()) {
    const std::optional<long long> p = ParseInteger(args.view_port);
    if (!p || *p < 0 || *p > 65535) Fail("--view", QuoteToken(args.view_port) + " is not a port (0..65535; 0 or none: a free one)");
    checked.port = int(*p);
  }
  RequireThreeJs();
  return checked;
}

// Where the scene's fields and pointshells are cached (--cache).
AssetOptions SessionAssetOptions(const SessionArgs& args) {
  AssetOptions options;
  options.cache_dir = args.cache;
  return options;
}

// The session's scene: the file, with --rate's cycle (1 / HZ) as its model.cycle_seconds and
// --budget as its node_budget. Throws Error naming the scene file when its cycle gives no loop
// rate.
Scene LoadSessionScene(const SessionArgs& args) {
  Scene scene = LoadScene(RequireDataFile(args.scene));
  if (args.rate > 0) scene.model.cycle_seconds = 1.0 / args.rate;
  if (args.budget >= 0) scene.node_budget = args.budget;
  (void)LoopRateOfCycle(scene.model.cycle_seconds, args.scene + ": model.cycle_seconds");
  // A session shorter than its first cycle would run none and report on nothing.
  if (args.duration > 0 && args.duration < scene.model.cycle_seconds) {
    char text[160];
    std::snprintf(text, sizeof text, "%g s is shorter than one haptic cycle (%s: model.cycle_seconds %g s): no cycle would run",
                  args.duration, args.scene.c_str(), scene.model.cycle_seconds);
    Fail("--duration", text);
  }
  return scene;
}

// The scene side of a session: the scene, its fields and pointshells (built or read from the
// cache), the contact model (--model, or the scene's first) and the haptic body's start pose
// (--touch: where it touches the other body, moved toward it; else the scene's pose).
//
// A scene of many bodies: the model is the scene's world (scene/scene_world.h WorldContactModel,
// every pair, the tool as the haptic body), its deformable bodies stepped by the world itself at
// the loop's rate (*WORLD_OUT: the world, which the model owns); --touch takes two bodies, and
// --view draws every body but marks no points.
std::unique_ptr<ContactModel> MakeSessionModel(const SessionArgs& args, const Scene& scene, SceneAssets& assets,
                                               const std::string& model_name, SceneWorld** world_out) {
  if (!scene.many_bodies()) return MakeSceneContactModel(model_name, scene, assets);
  if (args.touch > 0) {
    Fail(args.scene, "a scene of many bodies runs without --touch (it places one body touching the other); its tool "
                     "starts at its scene pose");
  }
  auto world = std::make_unique<SceneWorld>(scene, model_name, SessionAssetOptions(args));
  world->EnableDynamics(scene.model.cycle_seconds);
  *world_out = world.get();
  return std::make_unique<WorldContactModel>(std::move(world), model_name);
}

struct SessionScene {
  explicit SessionScene(const SessionArgs& args)
      : scene(LoadSessionScene(args)),
        assets(scene, SessionAssetOptions(args)),
        model_name(args.model.empty() ? scene.models.front() : args.model),
        model(MakeSessionModel(args, scene, assets, model_name, &world_)),
        X_WB_start(scene.field_body.pose) {
    if (args.touch > 0) {
      const Eigen::Vector3d toward = scene.pointshell_body.pose.translation - X_WB_start.translation;
      X_WB_start = TouchAlong(scene, assets, true, scene.pointshell_body.pose, X_WB_start, toward, args.touch,
                              args.scene + ": --touch");
    }
  }

  SceneWorld* world() const { return world_; }

  Scene scene;
  SceneAssets assets;
  std::string model_name;
  SceneWorld* world_ = nullptr;  // a scene of many bodies: the world MODEL closes the loop on
  std::unique_ptr<ContactModel> model;
  Pose X_WB_start;  // the haptic body's (the field body's) pose at the start
};

// The device of --device, its workspace centred on the haptic body's start pose.
struct SessionDevice {
  SessionDevice(const std::string& spec, const DeviceOptions& options, const Pose& X_WB_start)
      : device(MakeDevice(spec, options)), mapped(*device, X_WB_start) {}

  std::unique_ptr<HapticDevice> device;
  WorkspaceMappedDevice mapped;
};

// --view: the displayed pointshell points (the page's, same decimation), which the haptic
// thread marks with their contact state, a chunk per cycle.
std::unique_ptr<ContactPointMarks> MakeViewPointMarks(SessionScene& s) {
  return std::make_unique<ContactPointMarks>(DecimatePointshell(*s.assets.A.pointshell(), SceneViewOptions{}.max_points).index);
}

// The haptic cycle's configuration: the static body A, the coherence guard (the haptic body's
// real motion against the scene's max_point_speed), --k-vc, the deformable bodies' dynamics
// (stepped at the haptic rate) and the view's point marks (null without --view).
HapticCycleConfig MakeSessionCycleConfig(const SessionArgs& args, SessionScene& s, SceneDynamics& dynamics,
                                         ContactPointMarks* marks) {
  HapticCycleConfig config = SceneCycleConfig(s.scene, s.assets, &dynamics);
  if (args.k_vc > 0) config.coupling.k_vc = args.k_vc;
  config.point_marks = marks;
  return config;
}

// The loop's options: the scene's rate (1 / model.cycle_seconds, after --rate), --duration,
// --no-realtime (no SCHED_FIFO, no mlockall) and --cpu.
HapticLoopOptions SessionLoopOptions(const SessionArgs& args, const Scene& scene, int cpu) {
  HapticLoopOptions options;
  options.rate_hz = LoopRateOfCycle(scene.model.cycle_seconds, args.scene + ": model.cycle_seconds");
  options.spin_seconds = LoopSpinSeconds(options.rate_hz);
  options.duration_seconds = args.duration;
  options.try_realtime = !args.no_realtime;
  options.cpu = cpu;
  return options;
}

// --cpu N: takes the calling (main) thread off core N before the session starts any other
// thread, so that every thread it starts (field builds, device input, log consumer, viewer,
// the loop's watchdog) inherits a mask without N; the loop thread then pins itself to N.
void KeepSessionThreadsOffLoopCpu(int cpu) {
  if (cpu < 0) return;
  if (const int err = KeepThisThreadOffCpu(cpu); err != 0)
    Fail("--cpu", "cannot move the session's other threads off CPU " + std::to_string(cpu) + ": " +
                      std::strerror(err));
}

// The session log (--log): written to a temporary name and renamed when the session ends
// cleanly; on any failure the temporary is removed. Without --log every call does nothing.
class SessionLog {
 public:
  SessionLog(const SessionArgs& args, const SessionScene& s) : path_(args.log) {
    if (path_.empty()) return;
    output_.emplace(path_);
    out_.open(output_->temporary(), std::ios::trunc);
    if (!out_) Fail(path_, "cannot open the session log for writing");
    out_ << "# contactlab session log: scene " << s.scene.name << ", model " << s.model_name << ", device " << args.device
         << "\n"
         << kLogHeader;
  }

  // Consumer thread: one row per record, T0_NS the first record's time.
  void Write(const CycleRecord& r, std::int64_t t0_ns) {
    if (out_.is_open()) WriteRecord(out_, r, t0_ns);
  }

  // After the session: closes the log, checks that every write went through, and renames it
  // onto its name. Throws Error naming the log when a write failed.
  void Commit() {
    if (!out_.is_open()) return;
    out_.close();
    if (!out_) Fail(path_, "write failed (disk full or I/O error)");
    output_->Commit();
    std::printf("session log: %s\n", path_.c_str());
  }

 private:
  std::string path_;
  std::optional<TemporaryOutput> output_;
  std::ofstream out_;
};

// --view: the live view's snapshots (a history, and the publisher that fills it in session
// time) and its server (page and stream, loopback only).
struct SessionView {
  // A scene of many bodies: the contacts of its pairs the world copies every few cycles.
  std::unique_ptr<PairContactMarks> pair_contacts;
  std::unique_ptr<LiveMarks> marks;  // what the stream sends beside the snapshots, or null
  std::unique_ptr<LiveSnapshotHistory> snapshots;
  std::unique_ptr<LiveSnapshotPublisher> publisher;
  std::unique_ptr<LiveViewServer> server;
};

// Snapshots and marks are taken by session time, counted in cycles of the loop: 50 snapshots
// and at most 15 marks a second; a frame of pair contacts holds at most 4,096 of them.
constexpr double kSnapshotsPerSecond = 50, kMarksPerSecond = 15;
constexpr int kMaxViewPairContacts = 4096;

SessionView StartSessionView(const SessionArgs& args, SessionScene& s, int port, ContactPointMarks* marks,
                             double cycle_rate_hz) {
  const auto snapshot_every = std::max<std::int64_t>(1, std::llround(cycle_rate_hz / kSnapshotsPerSecond));
  const auto marks_every = std::max<std::int64_t>(1, std::int64_t(std::ceil(cycle_rate_hz / kMarksPerSecond)));
  // A scene of many bodies: every body from the world's assets, the tool (the haptic body) at
  // its start pose, and every pair's contacts from the world's cycles (set before the loop
  // starts); two bodies: the scene's page and its pointshell's marks.
  nlohmann::json data;
  SessionView view;
  if (SceneWorld* world = s.world()) {
    std::vector<BodyAssets*> bodies;
    for (int b = 0; b < world->body_count(); ++b) bodies.push_back(&world->body(b));
    data = ManyBodiesViewData(s.scene, s.model_name, bodies, SceneViewOptions{});
    view.pair_contacts = std::make_unique<PairContactMarks>(kMaxViewPairContacts, marks_every);
    world->SetPairContactMarks(view.pair_contacts.get());
    view.marks = std::make_unique<PairContactsFeed>(*view.pair_contacts);
  } else {
    data = SceneViewData(s.scene, s.assets, SceneViewOptions{}, BodyPoses{s.scene.pointshell_body.pose, s.X_WB_start});
    if (marks != nullptr) view.marks = std::make_unique<PointMarksFeed>(*marks);
  }
  data["title"] = s.scene.name + " (live)";
  const int haptic = s.scene.many_bodies() ? s.scene.tool : 1;
  data["live"] = {{"stream", "stream"}, {"haptic", haptic}, {"model", s.model_name}, {"device", args.device}};
  view.snapshots = std::make_unique<LiveSnapshotHistory>();
  view.publisher = std::make_unique<LiveSnapshotPublisher>(*view.snapshots, snapshot_every);
  view.server = std::make_unique<LiveViewServer>(ServedViewerPage(data), *view.snapshots, port, view.marks.get(),
                                                 marks_every);
  return view;
}

// The start lines on stdout: scene, model, device, length, rate and deformable bodies; where the
// device is (a udp device's bound port, also when udp:0 picked it); the view's address; with
// --cpu, the loop's core and the other threads' cores.
void PrintSessionStart(const SessionArgs& args, const SessionScene& s, const SceneDynamics& dynamics,
                       const HapticDevice& device, const LiveViewServer* server, int cpu, double rate_hz) {
  std::string deformable;
  if (dynamics.A) deformable += ", " + s.scene.pointshell_body.name + " deformable, r = " + std::to_string(dynamics.A->r());
  if (dynamics.B) deformable += ", " + s.scene.field_body.name + " deformable, r = " + std::to_string(dynamics.B->r());
  if (SceneWorld* world = s.world()) {
    int deforming = 0;
    for (int b = 0; b < world->body_count(); ++b) deforming += world->dynamics(b) != nullptr;
    deformable = ", " + std::to_string(world->body_count()) + " bodies, tool " + s.scene.field_body.name + ", " +
                 std::to_string(world->pair_count()) + " pairs, " + std::to_string(deforming) + " deformable";
  }
  std::printf("session: scene %s, model %s, device %s, %.1f s at %g Hz (Ctrl-C stops)%s\n", s.scene.name.c_str(),
              s.model_name.c_str(), args.device.c_str(), args.duration, rate_hz, deformable.c_str());
  std::printf("device: %s\n", device.description().c_str());
  if (server) std::printf("view: %s\n", server->url().c_str());
  if (cpu >= 0)
    std::printf("cpu: loop thread pinned to CPU %d, the session's other threads on CPUs %s\n", cpu,
                FormatCpuList(CpusOfThisThread()).c_str());
  std::fflush(stdout);
}

// The one-line status on stderr, every half second of session time: rate, 99th-percentile
// cycle time, points in contact, level rendered, clamps, coherence resets, contact faults
// (when any) and a rejecting device's counters (so that zero force has a reason).
class SessionStatusLine {
 public:
  explicit SessionStatusLine(bool quiet) : quiet_(quiet) { work_us_.reserve(4096); }

  // Consumer thread, every record in order.
  void Add(const CycleRecord& r) {
    if (window_start_ < 0) window_start_ = r.now_ns;
    work_us_.push_back(double(r.work_ns) * 1e-3);
    ++window_cycles_;
    points_ = r.points_in_contact;
    level_ = r.level_rendered;
    coherence_resets_ = r.coherence_resets;
    contact_faults_ = r.contact_faults;
    input_ = r.device_input;
    if (r.safety_flags & (kSafetyForceClamped | kSafetyTorqueClamped)) ++clamps_;
    if (r.now_ns - window_start_ > 500'000'000) {
      Print(r.now_ns);
      work_us_.clear();
      window_cycles_ = 0;
      window_start_ = r.now_ns;
    }
  }

  // Ends the line after the session.
  void Finish() const {
    if (!quiet_) std::fprintf(stderr, "\n");
  }

 private:
  void Print(std::int64_t now_ns) {
    if (quiet_ || work_us_.empty()) return;
    std::sort(work_us_.begin(), work_us_.end());
    const double p99 = work_us_[std::min(work_us_.size() - 1, std::size_t(0.99 * work_us_.size()))];
    const double rate = window_cycles_ / std::max(1e-9, double(now_ns - window_start_) * 1e-9);
    std::fprintf(stderr, "\r%7.0f Hz  p99 %7.1f us  contacts %5d  level %2d  clamps %6llu  coherence resets %lld", rate,
                 p99, points_, level_, static_cast<unsigned long long>(clamps_),
                 static_cast<long long>(coherence_resets_));
    if (contact_faults_ > 0) std::fprintf(stderr, "  contact faults %lld", static_cast<long long>(contact_faults_));
    if (input_.received > 0 || input_.rejected() > 0)
      std::fprintf(stderr, "  rejected %lld (malformed %lld, dup %lld, order %lld, stale %lld, future %lld) resyncs %lld",
                   static_cast<long long>(input_.rejected()), static_cast<long long>(input_.malformed),
                   static_cast<long long>(input_.duplicate), static_cast<long long>(input_.out_of_order),
                   static_cast<long long>(input_.stale), static_cast<long long>(input_.future),
                   static_cast<long long>(input_.resyncs));
    std::fprintf(stderr, "   ");
    std::fflush(stderr);
  }

  bool quiet_;
  std::vector<double> work_us_;  // this window's cycle times
  std::int64_t window_start_ = -1, window_cycles_ = 0;
  int points_ = 0, level_ = -1;
  std::uint64_t clamps_ = 0;
  std::int64_t coherence_resets_ = 0, contact_faults_ = 0;
  DeviceInputStats input_;
};

// Runs the haptic loop to its end while a consumer thread drains its records into the log,
// the status line and (with the view) the snapshot publisher; returns the loop's report.
HapticLoopReport RunSessionLoop(HapticLoop& loop, SessionLog& log, LiveSnapshotPublisher* live, bool quiet) {
  std::atomic<bool> done{false};
  std::thread consumer([&] {
    SessionStatusLine status(quiet);
    CycleRecord rec;
    std::int64_t t0 = -1;
    for (;;) {
      const bool finished = done.load();
      while (loop.records().TryPop(&rec)) {
        if (t0 < 0) t0 = rec.now_ns;
        log.Write(rec, t0);
        status.Add(rec);
        if (live) live->Offer(rec, t0);  // a snapshot every so many cycles
      }
      if (finished) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(live ? 2 : 5));
    }
    status.Finish();
  });
  const HapticLoopReport report = loop.Run();
  done.store(true);
  consumer.join();
  return report;
}

// The session, step by step: options, scene and model, device, cycle and loop, log, view;
// then the loop runs and the summary and the log close it.
void RunSession(const SessionArgs& args) {
  const CheckedOptions checked = CheckSessionOptions(args);
  KeepSessionThreadsOffLoopCpu(checked.cpu);
  SessionScene s(args);
  SessionDevice device(args.device, DeviceOptions{args.device_peers}, s.X_WB_start);
  // A scene of many bodies steps its deformable bodies in its world (MakeSessionModel).
  SceneDynamics dynamics = s.scene.many_bodies() ? SceneDynamics{} : MakeSceneDynamics(s.assets, s.scene.model.cycle_seconds);
  // The view's marks are of the one pointshell of two bodies; a scene of many bodies has a pair's each.
  std::unique_ptr<ContactPointMarks> marks = args.view && !s.scene.many_bodies() ? MakeViewPointMarks(s) : nullptr;
  HapticCycle cycle(device.mapped, s.model.get(), MakeSessionCycleConfig(args, s, dynamics, marks.get()));
  InstallStopSignalHandlers();
  const HapticLoopOptions loop_options = SessionLoopOptions(args, s.scene, checked.cpu);
  HapticLoop loop(cycle, loop_options);
  SessionLog log(args, s);
  const SessionView view =
      args.view ? StartSessionView(args, s, checked.port, marks.get(), loop_options.rate_hz) : SessionView{};
  PrintSessionStart(args, s, dynamics, *device.device, view.server.get(), checked.cpu, loop_options.rate_hz);
  // --view-wait: the session starts once its viewers opened the stream (or Ctrl-C: it ends
  // at once), so that they see it from its first cycle.
  if (checked.viewers > 0) {
    std::printf("view: waiting for %d viewer%s\n", checked.viewers, checked.viewers > 1 ? "s" : "");
    std::fflush(stdout);
    view.server->WaitForStreams(checked.viewers, StopSignalRequested);
  }

  const HapticLoopReport report = RunSessionLoop(loop, log, view.publisher.get(), args.quiet);
  if (view.server) view.server->Stop();
  std::printf("%s", FormatLoopReport(report).c_str());
  std::printf("  records dropped by the log consumer: %llu\n",
              static_cast<unsigned long long>(loop.records().dropped()));
  log.Commit();
}

const CommandRegistration kSessionCommands([](CLI::App& app) {
  auto args = std::make_shared<SessionArgs>();
  CLI::App* cmd = app.add_subcommand("session", "Run a live haptic session on a scene with a device at the scene's rate (1 kHz unless --rate)");
  cmd->add_option("SCENE", args->scene, "scene YAML file (its field body is the haptic body)")->required();
  cmd->add_option("--device", args->device,
                  "sim | sim:circle[:R[:PERIOD]] | replay:FILE.csv | udp:[ADDRESS:]PORT[:PEER] | spacenav | plugin:LIB.so");
  cmd->add_option("--device-peer", args->device_peers,
                  "IPv4 address of a device computer a udp device bound off the loopback accepts (repeatable; "
                  "required with udp:ADDRESS:PORT)");
  cmd->add_option("--duration", args->duration, "session length, seconds (at most 1e8)")
      ->check(CLI::PositiveNumber)
      ->check(CLI::Range(0.0, kMaxLoopSeconds));
  cmd->add_option("--rate", args->rate,
                  "the haptic loop's rate, Hz, 10 to 100000: sets the scene's model.cycle_seconds to 1 / HZ "
                  "(default: the scene's, 1 kHz unless it sets another)")
      ->check(CLI::Range(kMinLoopRateHz, kMaxLoopRateHz));
  cmd->add_option("--budget", args->budget,
                  "node budget per cycle (the paper's graceful degradation, sec. 3.3; 0: none); overrides the "
                  "scene's node_budget")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--log", args->log, "CSV log of poses, wrenches and timings (replayable trajectory)");
  cmd->add_option("--model", args->model, "contact model (default: the scene's first)");
  cmd->add_option("--k-vc", args->k_vc, "virtual coupling stiffness, N/m")->check(CLI::PositiveNumber);
  cmd->add_option("--touch", args->touch,
                  "start the haptic body in contact: moved toward the other body until this deep, metres")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--cache", args->cache, "cache folder for fields and pointshells");
  cmd->add_flag("--no-realtime", args->no_realtime, "do not try SCHED_FIFO / mlockall");
  cmd->add_flag("--quiet", args->quiet, "no live status line");
  CLI::Option* cpu = cmd->add_option("--cpu", args->cpu,
                  "pin the haptic loop thread to CPU N and keep every other thread of the session off it "
                  "(docs/sessions.md: isolate N first)");
  CLI::Option* view = cmd->add_option("--view", args->view_port,
                                      "serve a live 3D view on http://127.0.0.1:PORT/ (no PORT or 0: a free port, printed)")
                          ->expected(0, 1);
  CLI::Option* view_wait =
      cmd->add_option("--view-wait", args->view_wait_count,
                      "with --view: start the session once N viewers (default 1) opened the live view's stream")
          ->expected(0, 1);
  cmd->callback([args, view, view_wait, cpu] {
    args->cpu_given = cpu->count() > 0;
    args->view = view->count() > 0;
    args->view_wait = view_wait->count() > 0;
    RunSession(*args);
  });
});

}  // namespace
}  // namespace contactlab::cli
