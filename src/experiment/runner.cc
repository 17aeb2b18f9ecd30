#include "experiment/runner.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "contact/pointshell_contact_model.h"
#include "experiment/contact_placement.h"
#include "experiment/metrics.h"
#include "experiment/model_factory.h"
#include "experiment/source_revision.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/progress.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

// --- CSV text --------------------------------------------------------------------------

std::string AxisHeader(const ExperimentConfig& config) {
  std::string h;
  for (const SweepAxis& a : config.sweep) h += a.name + ",";
  return h;
}

std::string AxisValues(const Job& job) {
  std::string v;
  for (const auto& [axis, value] : job.axis_values) v += value + ",";
  return v;
}

std::string CyclesHeader(const ExperimentConfig& config) {
  return "experiment,job," + AxisHeader(config) +
         "model,cycle,t,x,y,z,fx,fy,fz,tx,ty,tz,contacts,nodes,level,max_penetration,depth_voxels,time_us,"
         "ref_fx,ref_fy,ref_fz\n";
}

std::string SummaryHeader(const ExperimentConfig& config) {
  return "experiment,job," + AxisHeader(config) +
         "model,points,cycles,max_jump_N,lipschitz_N_per_m,hf_share,median_us,p99_us,max_us,mean_nodes,"
         "level_switches_per_s,rms_rel_error,max_dir_error_deg,max_force_N,mean_force_N,max_depth_voxels\n";
}

void AppendCycles(std::string& out, const ExperimentConfig& config, const JobResult& r) {
  const std::string prefix = config.name + "," + std::to_string(r.job.index) + "," + AxisValues(r.job);
  char buf[768];
  for (const CycleRow& c : r.cycles) {
    int n = std::snprintf(buf, sizeof buf,
                          "%s,%lld,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%lld,%d,%.6g,%.4g,%.3f,",
                          c.model.c_str(), static_cast<long long>(c.cycle), c.t, c.position.x(), c.position.y(),
                          c.position.z(), c.force.x(), c.force.y(), c.force.z(), c.torque.x(), c.torque.y(),
                          c.torque.z(), c.contacts, static_cast<long long>(c.nodes), c.level, c.max_penetration,
                          c.depth_voxels, c.time_us);
    out += prefix;
    out.append(buf, std::size_t(n));
    if (c.has_reference) {
      n = std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g\n", c.reference_force.x(), c.reference_force.y(),
                        c.reference_force.z());
      out.append(buf, std::size_t(n));
    } else {
      out += ",,\n";
    }
  }
}

void AppendSummary(std::string& out, const ExperimentConfig& config, const JobResult& r) {
  const std::string prefix = config.name + "," + std::to_string(r.job.index) + "," + AxisValues(r.job);
  char buf[768];
  for (const SummaryRow& s : r.summary) {
    const int n = std::snprintf(buf, sizeof buf, "%s,%d,%lld,%.6g,%.6g,%.6g,%.3f,%.3f,%.3f,%.1f,%.3f,%.6g,%.4g,%.6g,%.6g,%.4g\n",
                                s.model.c_str(), s.points, static_cast<long long>(s.cycles), s.max_jump, s.lipschitz,
                                s.hf_share, s.median_us, s.p99_us, s.max_us, s.mean_nodes, s.level_switches_per_s,
                                s.rms_rel_error, s.max_dir_error_deg, s.max_force, s.mean_force, s.max_depth_voxels);
    out += prefix;
    out.append(buf, std::size_t(n));
  }
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

// convergence.csv from summary.csv text: for each model and each combination of the sweep
// axes other than "points", the error against the reference as the pointshell grows and the
// fitted order (error ~ points^-order).
std::string ConvergenceCsv(const std::string& summary_csv) {
  std::istringstream in(summary_csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = SplitCsv(line);
  auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    return it == header.end() ? -1 : int(it - header.begin());
  };
  const int c_model = col("model"), c_points = col("points"), c_err = col("rms_rel_error"), c_job = col("job");
  std::map<std::string, std::vector<std::pair<double, double>>> groups;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = SplitCsv(line);
    if (int(cells.size()) != int(header.size())) continue;
    std::string key = cells[c_model];
    for (int c = c_job + 1; c < c_model; ++c) {
      if (header[c] != "points") key += ";" + header[c] + "=" + cells[c];
    }
    const double err = std::stod(cells[c_err]);
    if (err >= 0) groups[key].emplace_back(std::stod(cells[c_points]), err);
  }
  std::string out = "group,samples,fitted_order,points,errors\n";
  for (auto& [key, pairs] : groups) {
    std::sort(pairs.begin(), pairs.end());
    std::vector<double> xs, ys;
    std::string pts, errs;
    for (auto [x, y] : pairs) {
      xs.push_back(x), ys.push_back(y);
      char b[48];
      std::snprintf(b, sizeof b, "%s%d", pts.empty() ? "" : " ", int(x));
      pts += b;
      std::snprintf(b, sizeof b, "%s%.4g", errs.empty() ? "" : " ", y);
      errs += b;
    }
    char b[64];
    std::snprintf(b, sizeof b, "%.4g", FittedOrder(xs, ys));
    out += key + "," + std::to_string(pairs.size()) + "," + b + "," + pts + "," + errs + "\n";
  }
  return out;
}

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

nlohmann::json MetaJson(const ExperimentConfig& config, const std::vector<int>& jobs, double wall_seconds,
                        int parallel) {
  nlohmann::json j;
  j["experiment"] = config.name;
  j["description"] = config.description;
  j["config_file"] = config.file;
  j["resolved_config"] = config.resolved_yaml;
  j["jobs"] = jobs;
  j["parallel_jobs"] = parallel;
  j["wall_seconds"] = wall_seconds;
  j["git_commit"] = ConfigRevision(config.file);  // the checkout holding the config
  j["build_commit"] = BuildRevision();             // the checkout the binary was built from
  j["contactlab_version"] = CONTACTLAB_VERSION;
  j["compiler"] = CONTACTLAB_COMPILER;
  j["compiler_flags"] = CONTACTLAB_CXX_FLAGS;
  j["build_type"] = CONTACTLAB_BUILD_TYPE;
  j["library_versions"] = CONTACTLAB_LIBRARY_VERSIONS;
  j["cpu"] = CpuModel();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  char host[256] = {0};
  ::gethostname(host, sizeof host - 1);
  j["host"] = host;
  const std::time_t now = std::time(nullptr);
  char stamp[64];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["finished_utc"] = stamp;
  return j;
}

}  // namespace

JobResult RunJob(const ExperimentConfig& config, const Job& job, const RunOptions& options) {
  JobResult result;
  result.job = job;
  const Scene& scene = job.scene;
  SceneAssets assets(scene, options.assets);
  const bool moving_is_B = scene.field_body.name == job.moving_body;
  Pose X_WA0 = scene.pointshell_body.pose, X_WB0 = scene.field_body.pose;
  // touch: true moves the body along the trajectory's direction until the deepest point of
  // the paper's model (linear, deepest level) is touch_depth deep; the trajectory starts there.
  // direction: toward points from the moving body to the other body's origin.
  YAML::Node tyaml = YAML::Clone(config.trajectory_node.yaml());
  const Pose& X_moving0 = moving_is_B ? X_WB0 : X_WA0;
  const Pose& X_other0 = moving_is_B ? X_WA0 : X_WB0;
  if (tyaml["direction"] && tyaml["direction"].IsScalar()) {
    const Eigen::Vector3d toward = (X_other0.translation - X_moving0.translation).normalized();
    tyaml["direction"] = std::vector<double>{toward.x(), toward.y(), toward.z()};
  }
  const ConfigNode tn(tyaml, std::make_shared<const std::string>(config.file), "trajectory");
  const Trajectory trajectory = ParseTrajectory(tn);
  if (tn.Bool("touch", false)) {
    Eigen::Vector3d dir(0, 0, -1);
    if (auto d = tn.Find("direction")) {
      const std::vector<double> v = d->AsDoubles();
      dir = Eigen::Vector3d(v[0], v[1], v[2]).normalized();
    }
    const double depth = tn.Positive("touch_depth", 1e-4);
    const Pose moved = TouchAlong(scene, assets, moving_is_B, X_WA0, X_WB0, dir, depth,
                                  config.file + ": job " + std::to_string(job.index));
    (moving_is_B ? X_WB0 : X_WA0) = moved;
  }
  const Pose start = moving_is_B ? X_WB0 : X_WA0;
  const double dt = scene.model.cycle_seconds;
  const std::int64_t cycles = std::int64_t(std::floor(trajectory.duration() / dt + 1e-9)) + 1;

  // The reference: a model of the same scene, or of a denser version of it.
  std::unique_ptr<ContactModel> reference;
  std::unique_ptr<SceneAssets> reference_assets;
  if (!config.reference_model.empty()) {
    Scene ref_scene = scene;
    if (config.reference_points > 0) ref_scene.pointshell_body.pointshell.points = config.reference_points;
    if (config.reference_levels > 0) ref_scene.pointshell_body.pointshell.levels = config.reference_levels;
    if (config.reference_resolution > 0) ref_scene.field_body.field.resolution = config.reference_resolution;
    ref_scene.model.level = -1;
    ref_scene.model.node_budget = 0;
    reference_assets = std::make_unique<SceneAssets>(ref_scene, options.assets);
    reference = MakeContactModel(config.reference_model, ref_scene, *reference_assets);
  }

  for (const std::string& name : job.models) {
    std::unique_ptr<ContactModel> model = MakeContactModel(name, scene, assets);
    const bool pointshell_like = name.rfind("pointshell", 0) == 0 || name.rfind("vps", 0) == 0;
    const double spacing = pointshell_like ? assets.B.field()->spacing() : 0.0;
    std::vector<Eigen::Vector3d> forces, refs;
    std::vector<Pose> poses;
    std::vector<bool> has_ref;
    std::vector<double> times;
    std::vector<int> levels;
    double nodes_sum = 0, max_depth = 0;
    for (std::int64_t k = 0; k < cycles; ++k) {
      // The moving body follows the trajectory from its start pose; the other stays put.
      const Pose d = trajectory.At(trajectory.start_time() + double(k) * dt);
      const Pose X_moving{(d.rotation * start.rotation).normalized(), start.translation + d.translation};
      ContactQuery q;
      q.X_WA = moving_is_B ? X_WA0 : X_moving;
      q.X_WB = moving_is_B ? X_moving : X_WB0;
      q.cycle = k;
      q.node_budget = scene.model.node_budget;
      const auto t0 = std::chrono::steady_clock::now();
      const ContactResult r = model->Evaluate(q);
      const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      // Wrench on the moving body about its own origin.
      auto on_moving = [&](const Wrench& on_B, Eigen::Vector3d* F, Eigen::Vector3d* T) {
        if (moving_is_B) {
          *F = on_B.force;
          *T = on_B.torque;
        } else {
          *F = -on_B.force;
          *T = -on_B.torque - (q.X_WB.translation - q.X_WA.translation).cross(on_B.force);
        }
      };
      CycleRow row;
      row.job = job.index;
      row.model = name;
      row.cycle = k;
      row.t = double(k) * dt;
      row.position = X_moving.translation;
      on_moving(r.on_B, &row.force, &row.torque);
      row.contacts = r.stats.points_in_contact;
      row.nodes = r.stats.nodes_visited;
      row.level = r.stats.level_rendered;
      row.max_penetration = r.stats.max_penetration;
      row.depth_voxels = spacing > 0 ? r.stats.max_penetration / spacing : 0.0;
      row.time_us = us;
      if (reference && k % config.reference_every == 0) {
        Eigen::Vector3d T;
        ContactQuery rq = q;
        rq.node_budget = 0;
        on_moving(reference->Evaluate(rq).on_B, &row.reference_force, &T);
        row.has_reference = true;
      }
      forces.push_back(row.force);
      refs.push_back(row.reference_force);
      has_ref.push_back(row.has_reference);
      poses.push_back(X_moving);
      times.push_back(us);
      levels.push_back(row.level);
      nodes_sum += double(row.nodes);
      max_depth = std::max(max_depth, row.depth_voxels);
      result.cycles.push_back(row);
    }
    // Per-model metrics over the trajectory.
    SummaryRow s;
    s.job = job.index;
    s.model = name;
    s.points = scene.pointshell_body.pointshell.points;
    s.cycles = cycles;
    const double radius = assets.A.mesh()->Bounds().size().norm() / 2;
    const ContinuityMetrics c = ForceContinuity(forces, poses, dt, radius, config.cutoff_hz);
    s.max_jump = c.max_jump;
    s.lipschitz = c.lipschitz;
    s.hf_share = c.high_frequency_share;
    const TimingMetrics t = Timing(times, levels, dt);
    s.median_us = t.median_us;
    s.p99_us = t.p99_us;
    s.max_us = t.max_us;
    s.level_switches_per_s = t.level_switches_per_second;
    s.mean_nodes = nodes_sum / double(cycles);
    if (reference) {
      const ErrorMetrics e = ErrorAgainstReference(forces, refs, has_ref);
      s.rms_rel_error = e.rms_relative;
      s.max_dir_error_deg = e.max_direction_deg;
    }
    for (const Eigen::Vector3d& f : forces) {
      s.max_force = std::max(s.max_force, f.norm());
      s.mean_force += f.norm() / double(cycles);
    }
    s.max_depth_voxels = max_depth;
    result.summary.push_back(s);
  }
  return result;
}

std::vector<SummaryRow> RunExperiment(const ExperimentConfig& config, const RunOptions& options,
                                      const std::vector<int>& job_indices) {
  const std::vector<Job> all = ExpandJobs(config);
  std::vector<int> indices = job_indices;
  if (indices.empty()) {
    for (const Job& j : all) indices.push_back(j.index);
  }
  for (int i : indices) {
    if (i < 0 || i >= int(all.size())) {
      Fail(config.file, "job " + std::to_string(i) + " does not exist (the sweep has " + std::to_string(all.size()) +
                            " jobs: 0.." + std::to_string(int(all.size()) - 1) + ")");
    }
  }
  int parallel = options.parallel_jobs;
  if (parallel <= 0) parallel = config.timing ? 1 : int(std::max(1u, std::thread::hardware_concurrency()));
  parallel = std::min<int>(parallel, int(indices.size()));

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<JobResult> results(indices.size());
  {
    Progress progress("experiment " + config.name, std::int64_t(indices.size()));
    if (!options.progress) progress.Finish();
    // A failing job does not cancel the others (whose builds are isolated from cancellation
    // anyway): each job's exception is kept, every job finishes, and the first error in job
    // order is rethrown, so the reported error does not depend on thread timing.
    std::vector<std::exception_ptr> errors(indices.size());
    tbb::task_arena arena(std::max(1, parallel));
    arena.execute([&] {
      tbb::parallel_for(std::size_t(0), indices.size(), [&](std::size_t i) {
        try {
          results[i] = RunJob(config, all[std::size_t(indices[i])], options);
        } catch (...) {
          errors[i] = std::current_exception();
        }
        if (options.progress) progress.Advance();
      });
    });
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Everything is formatted in memory and written at the end, each file atomically.
  std::string cycles = CyclesHeader(config), summary = SummaryHeader(config);
  std::vector<SummaryRow> rows;
  for (const JobResult& r : results) {
    AppendCycles(cycles, config, r);
    AppendSummary(summary, config, r);
    rows.insert(rows.end(), r.summary.begin(), r.summary.end());
  }
  fs::create_directories(options.out_dir);
  WriteFileAtomically(options.out_dir / "cycles.csv", cycles);
  WriteFileAtomically(options.out_dir / "summary.csv", summary);
  WriteFileAtomically(options.out_dir / "convergence.csv", ConvergenceCsv(summary));
  WriteFileAtomically(options.out_dir / "meta.json", MetaJson(config, indices, wall, parallel).dump(2) + "\n");
  return rows;
}

void MergeResults(const std::vector<fs::path>& job_dirs, const fs::path& out_dir) {
  if (job_dirs.empty()) Fail(out_dir.string(), "nothing to merge");
  std::string cycles, summary;
  std::string cycles_header, summary_header;
  nlohmann::json meta;
  std::vector<int> jobs;
  double wall = 0;
  for (const fs::path& dir : job_dirs) {
    for (const char* name : {"cycles.csv", "summary.csv", "meta.json"}) {
      if (!fs::exists(dir / name)) Fail(dir.string(), std::string("is missing ") + name + " (an unfinished job?)");
    }
    auto take = [&](const char* name, std::string& header, std::string& body) {
      const std::string text = ReadWholeFile(dir / name);
      const auto eol = text.find('\n');
      const std::string h = text.substr(0, eol + 1);
      if (header.empty()) {
        header = h;
      } else if (h != header) {
        Fail((dir / name).string(), "its columns differ from the first folder's");
      }
      body += text.substr(eol + 1);
    };
    take("cycles.csv", cycles_header, cycles);
    take("summary.csv", summary_header, summary);
    nlohmann::json m;
    try {
      m = nlohmann::json::parse(ReadWholeFile(dir / "meta.json"));
    } catch (const nlohmann::json::exception& e) {
      Fail((dir / "meta.json").string(), std::string("not valid JSON: ") + e.what());
    }
    if (meta.is_null()) meta = m;
    if (m.value("experiment", "") != meta.value("experiment", "")) {
      Fail((dir / "meta.json").string(), "belongs to another experiment");
    }
    for (int j : m["jobs"]) jobs.push_back(j);
    wall += m.value("wall_seconds", 0.0);
  }
  meta["jobs"] = jobs;
  meta["wall_seconds"] = wall;
  meta["merged_from"] = nlohmann::json::array();
  for (const fs::path& d : job_dirs) meta["merged_from"].push_back(d.string());
  fs::create_directories(out_dir);
  WriteFileAtomically(out_dir / "cycles.csv", cycles_header + cycles);
  WriteFileAtomically(out_dir / "summary.csv", summary_header + summary);
  WriteFileAtomically(out_dir / "convergence.csv", ConvergenceCsv(summary_header + summary));
  WriteFileAtomically(out_dir / "meta.json", meta.dump(2) + "\n");
}

}  // namespace contactlab
