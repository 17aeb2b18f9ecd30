// The many-bodies study (many_bodies_study.h): one job builds the scene's world once per model,
// moves the tool along the trajectory through it and records the totals, every near pair and
// every deformable body, cycle by cycle.
#include "experiment/studies/many_bodies/many_bodies_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "contact/coherence_guard.h"
#include "experiment/csv_line.h"
#include "experiment/result_table.h"
#include "experiment/run_metadata.h"
#include "experiment/study.h"
#include "scene/scene_world.h"
#include "scene/trajectory.h"
#include "util/error.h"

namespace contactlab {
namespace {

using Clock = std::chrono::steady_clock;

// The job's trajectory (the study requires one; parsed with the job), checked for what a scene
// of many bodies can give it.
const TrajectorySpec& WorldTrajectory(const Job& job) {
  const TrajectorySpec& spec = *job.trajectory;
  if (spec.toward) {
    job.trajectory_node.Get("direction").Fail(
        "toward points at the other of two bodies; in a scene of many bodies give the direction as a vector");
  }
  if (spec.touch) {
    job.trajectory_node.Get("touch").Fail(
        "places the moving body touching the other of two bodies; a scene of many bodies starts the tool at its "
        "scene pose");
  }
  return spec;
}

// The quantile Q of V (reordered), 0 for none.
double Quantile(std::vector<double>* v, double q) {
  if (v->empty()) return 0;
  const std::size_t k = std::min(v->size() - 1, std::size_t(std::floor(q * double(v->size()))));
  std::nth_element(v->begin(), v->begin() + std::ptrdiff_t(k), v->end());
  return (*v)[k];
}

// One model's run of the job: the tool along the trajectory through a world of its own.
void RunModel(const Job& job, const RunOptions& options, const Trajectory& trajectory, int m,
              WorldJobResult* out) {
  const Scene& scene = job.scene;
  SceneWorld world(scene, out->models[std::size_t(m)], options.assets);
  world.EnableDynamics(scene.model.cycle_seconds);
  for (int p = 0; p < world.pair_count(); ++p) {
    const OrderedPair& pair = world.pair(p);
    out->pairs.push_back({scene.bodies[std::size_t(pair.A)].name, scene.bodies[std::size_t(pair.B)].name, pair.model});
  }
  const BodySpec& tool = scene.bodies[std::size_t(scene.tool)];
  const double dt = scene.model.cycle_seconds;
  if (!(trajectory.duration() / dt <= kMaxTrajectorySamples)) {
    Fail(job.config.file(), "trajectory.duration at model.cycle_seconds is more cycles than the limit of 1e8");
  }
  const std::int64_t cycles = std::int64_t(std::floor(trajectory.duration() / dt + 1e-9)) + 1;
  CoherenceGuard guard(scene.model.max_point_speed, dt, world.body(scene.tool).mesh()->MaxVertexRadius(),
                       scene.file + ": body '" + tool.name + "'");
  std::vector<int> deformable;
  for (int b = 0; b < world.body_count(); ++b) {
    if (world.dynamics(b) != nullptr) deformable.push_back(b);
  }
  out->cycles.reserve(out->cycles.size() + std::size_t(cycles));
  out->body_rows.reserve(out->body_rows.size() + std::size_t(cycles) * deformable.size());
  WorldSummaryRow sum;
  sum.model = m;
  sum.bodies = world.body_count();
  sum.pairs = world.pair_count();
  sum.deformable = int(deformable.size());
  sum.cycles = cycles;
  std::vector<double> times;
  times.reserve(std::size_t(cycles));
  double near_total = 0;
  std::int64_t touching_cycles = 0, degraded_cycles = 0;
  for (std::int64_t k = 0; k < cycles; ++k) {
    const double t = double(k) * dt;
    const Pose d = trajectory.At(trajectory.start_time() + t);
    const Pose X{(d.rotation * tool.pose.rotation).normalized(), tool.pose.translation + d.translation};
    WorldCycleRow row;
    row.model = m;
    row.cycle = k;
    row.t = t;
    row.position = X.translation;
    row.rotation = X.rotation;
    if (k == 0) guard.Start(X);
    row.coherence_reset = guard.Check(X);
    if (row.coherence_reset) world.ForgetTemporalState();
    const auto t0 = Clock::now();
    const WorldResult& r = world.Evaluate(X, k);
    row.time_us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    row.force = r.on_tool.force;
    row.torque = r.on_tool.torque;
    row.pairs_near = r.stats.pairs_near;
    row.pairs_touching = r.stats.pairs_touching;
    row.pairs_degraded = r.stats.pairs_degraded;
    row.faults = r.stats.sum.faults;
    row.beyond_bound = r.stats.bodies_beyond_bound;
    row.contacts = r.stats.sum.points_in_contact;
    row.nodes = r.stats.sum.nodes_visited;
    row.max_penetration = r.stats.sum.max_penetration;
    out->cycles.push_back(row);
    for (const int p : world.near_pairs()) {
      const PairOutcome& o = world.outcome(p);
      const ContactStats& st = o.result.stats;
      out->pair_rows.push_back({m, k, t, p, o.budget, st.points_in_contact, st.nodes_visited,
                                st.level_rendered, st.degraded, st.max_penetration, o.result.on_B.force,
                                o.result.on_B.torque});
    }
    for (const int b : deformable) {
      BodyDynamics& dyn = *world.dynamics(b);
      const double u = dyn.MaxDisplacement();
      const auto& q = dyn.state().q;
      out->body_rows.push_back(
          {m, k, t, b, u, dyn.PotentialEnergy(), dyn.KineticEnergy(), std::vector<double>(q.data(), q.data() + q.size())});
      sum.max_displacement = std::max(sum.max_displacement, u);
    }
    times.push_back(row.time_us);
    near_total += row.pairs_near;
    touching_cycles += row.pairs_touching > 0;
    degraded_cycles += row.pairs_degraded > 0;
    sum.max_pairs_touching = std::max(sum.max_pairs_touching, row.pairs_touching);
    sum.max_force = std::max(sum.max_force, row.force.norm());
    sum.faults += row.faults;
    sum.coherence_resets += row.coherence_reset;
    sum.beyond_bound_cycles += row.beyond_bound > 0;
  }
  sum.mean_pairs_near = near_total / double(cycles);
  sum.touching_share = double(touching_cycles) / double(cycles);
  sum.degraded_share = double(degraded_cycles) / double(cycles);
  sum.median_us = Quantile(&times, 0.5);
  sum.p99_us = Quantile(&times, 0.99);
  sum.p999_us = Quantile(&times, 0.999);
  sum.max_us = *std::max_element(times.begin(), times.end());
  out->summary.push_back(sum);
}

// A row and the job's result it belongs to, as the column writers see it.
template <class Row>
struct Bound {
  const WorldJobResult& job;
  const Row& row;
};

using CycleCell = Bound<WorldCycleRow>;
const TableColumn<CycleCell> kCycleColumns[] = {
    {"model", "", "the model of the pairs without their own",
     [](const CycleCell& c, CsvLine& l) { l.Text(c.job.models[std::size_t(c.row.model)]); }},
    {"cycle", "", "haptic cycle index", [](const CycleCell& c, CsvLine& l) { l.Int(c.row.cycle); }},
    {"t", "s", "time along the trajectory", [](const CycleCell& c, CsvLine& l) { l.Num("%.6f", c.row.t); }},
    {"x", "m", "the tool's origin, world x", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.position.x()); }},
    {"y", "m", "the tool's origin, world y", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.position.y()); }},
    {"z", "m", "the tool's origin, world z", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.position.z()); }},
    {"qw", "", "the tool's orientation, quaternion w", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.rotation.w()); }},
    {"qx", "", "quaternion x", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.rotation.x()); }},
    {"qy", "", "quaternion y", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.rotation.y()); }},
    {"qz", "", "quaternion z", [](const CycleCell& c, CsvLine& l) { l.Num("%.7g", c.row.rotation.z()); }},
    {"fx", "N", "force on the tool summed over its pairs, world x",
     [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.force.x()); }},
    {"fy", "N", "world y", [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.force.y()); }},
    {"fz", "N", "world z", [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.force.z()); }},
    {"tx", "N m", "torque on the tool about its origin, world x",
     [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.torque.x()); }},
    {"ty", "N m", "world y", [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.torque.y()); }},
    {"tz", "N m", "world z", [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.torque.z()); }},
    {"pairs_near", "", "pairs whose broad-phase boxes overlapped (reached their models)",
     [](const CycleCell& c, CsvLine& l) { l.Int(c.row.pairs_near); }},
    {"pairs_touching", "", "pairs whose model found contact",
     [](const CycleCell& c, CsvLine& l) { l.Int(c.row.pairs_touching); }},
    {"pairs_degraded", "", "pairs the cycle's one node budget made degrade",
     [](const CycleCell& c, CsvLine& l) { l.Int(c.row.pairs_degraded); }},
    {"faults", "", "queries a pair's model refused", [](const CycleCell& c, CsvLine& l) { l.Int(c.row.faults); }},
    {"contacts", "", "points (or contacts) in contact, summed over the pairs",
     [](const CycleCell& c, CsvLine& l) { l.Int(c.row.contacts); }},
    {"nodes", "", "nodes visited, summed over the pairs", [](const CycleCell& c, CsvLine& l) { l.Int(c.row.nodes); }},
    {"max_penetration", "m", "deepest penetration over the pairs",
     [](const CycleCell& c, CsvLine& l) { l.Num("%.6g", c.row.max_penetration); }},
    {"time_us", "us", "the world's cycle: broad phase, every near pair, the deformable steps",
     [](const CycleCell& c, CsvLine& l) { l.Num("%.2f", c.row.time_us); }},
    {"coherence_reset", "", "1 when the tool outran max_point_speed and every pair's coherence was forgotten",
     [](const CycleCell& c, CsvLine& l) { l.Int(c.row.coherence_reset); }},
    {"beyond_bound", "", "deformable bodies displaced past their deformation_bound (a pair of theirs may have been missed)",
     [](const CycleCell& c, CsvLine& l) { l.Int(c.row.beyond_bound); }},
};

using PairCell = Bound<WorldPairRow>;
const WorldPairName& NameOf(const PairCell& c) {
  return c.job.pairs[std::size_t(c.row.model) * c.job.job.scene.pairs.size() + std::size_t(c.row.pair)];
}
const TableColumn<PairCell> kPairColumns[] = {
    {"model", "", "the model of the pairs without their own",
     [](const PairCell& c, CsvLine& l) { l.Text(c.job.models[std::size_t(c.row.model)]); }},
    {"cycle", "", "haptic cycle index", [](const PairCell& c, CsvLine& l) { l.Int(c.row.cycle); }},
    {"t", "s", "time along the trajectory", [](const PairCell& c, CsvLine& l) { l.Num("%.6f", c.row.t); }},
    {"pair", "", "the pair's index among the scene's pairs",
     [](const PairCell& c, CsvLine& l) { l.Int(c.row.pair); }},
    {"body_a", "", "the pair's body A (its model's order)", [](const PairCell& c, CsvLine& l) { l.Text(NameOf(c).body_A); }},
    {"body_b", "", "the pair's body B", [](const PairCell& c, CsvLine& l) { l.Text(NameOf(c).body_B); }},
    {"pair_model", "", "the pair's model", [](const PairCell& c, CsvLine& l) { l.Text(NameOf(c).model); }},
    {"node_budget", "", "its share of the cycle's node budget (0: unlimited)",
     [](const PairCell& c, CsvLine& l) { l.Int(c.row.budget); }},
    {"contacts", "", "points (or contacts) in contact", [](const PairCell& c, CsvLine& l) { l.Int(c.row.contacts); }},
    {"nodes", "", "nodes visited", [](const PairCell& c, CsvLine& l) { l.Int(c.row.nodes); }},
    {"level", "", "deepest tree level completed (-1: not a tree model)",
     [](const PairCell& c, CsvLine& l) { l.Int(c.row.level); }},
    {"degraded", "", "steps the budget made its model degrade (the model's own unit)",
     [](const PairCell& c, CsvLine& l) { l.Int(c.row.degraded); }},
    {"max_penetration", "m", "its deepest penetration", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.max_penetration); }},
    {"fx", "N", "force on the pair's B, world x", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.force.x()); }},
    {"fy", "N", "world y", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.force.y()); }},
    {"fz", "N", "world z", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.force.z()); }},
    {"tx", "N m", "torque on B about its origin, world x", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.torque.x()); }},
    {"ty", "N m", "world y", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.torque.y()); }},
    {"tz", "N m", "world z", [](const PairCell& c, CsvLine& l) { l.Num("%.6g", c.row.torque.z()); }},
};

using BodyCell = Bound<WorldBodyRow>;
const TableColumn<BodyCell> kBodyColumns[] = {
    {"model", "", "the model of the pairs without their own",
     [](const BodyCell& c, CsvLine& l) { l.Text(c.job.models[std::size_t(c.row.model)]); }},
    {"cycle", "", "haptic cycle index", [](const BodyCell& c, CsvLine& l) { l.Int(c.row.cycle); }},
    {"t", "s", "time along the trajectory", [](const BodyCell& c, CsvLine& l) { l.Num("%.6f", c.row.t); }},
    {"body", "", "the deformable body",
     [](const BodyCell& c, CsvLine& l) { l.Text(c.job.job.scene.bodies[std::size_t(c.row.body)].name); }},
    {"max_displacement", "m", "largest displacement of its simulation mesh's vertices after the cycle's step",
     [](const BodyCell& c, CsvLine& l) { l.Num("%.6g", c.row.max_displacement); }},
    {"elastic_energy_J", "J", "its elastic energy (mass-normalised coordinates)",
     [](const BodyCell& c, CsvLine& l) { l.Num("%.6g", c.row.elastic_energy); }},
    {"kinetic_energy_J", "J", "its kinetic energy", [](const BodyCell& c, CsvLine& l) { l.Num("%.6g", c.row.kinetic_energy); }},
    {"q", "", "its reduced coordinates q_1 .. q_r after the step, space-separated (mass-normalised)",
     [](const BodyCell& c, CsvLine& l) { l.Numbers("%.9g", c.row.q); }},
};

using SummaryCell = Bound<WorldSummaryRow>;
const TableColumn<SummaryCell> kSummaryColumns[] = {
    {"model", "", "the model of the pairs without their own",
     [](const SummaryCell& c, CsvLine& l) { l.Text(c.job.models[std::size_t(c.row.model)]); }},
    {"bodies", "", "bodies in the scene", [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.bodies); }},
    {"pairs", "", "pairs in the scene", [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.pairs); }},
    {"deformable", "", "deformable bodies stepped", [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.deformable); }},
    {"cycles", "", "cycles along the trajectory", [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.cycles); }},
    {"median_us", "us", "median time of the world's cycle", [](const SummaryCell& c, CsvLine& l) { l.Num("%.2f", c.row.median_us); }},
    {"p99_us", "us", "its 99th percentile", [](const SummaryCell& c, CsvLine& l) { l.Num("%.2f", c.row.p99_us); }},
    {"p999_us", "us", "its 99.9th percentile", [](const SummaryCell& c, CsvLine& l) { l.Num("%.2f", c.row.p999_us); }},
    {"max_us", "us", "its largest", [](const SummaryCell& c, CsvLine& l) { l.Num("%.2f", c.row.max_us); }},
    {"mean_pairs_near", "", "pairs near per cycle, mean", [](const SummaryCell& c, CsvLine& l) { l.Num("%.4g", c.row.mean_pairs_near); }},
    {"max_pairs_touching", "", "most pairs in contact in one cycle",
     [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.max_pairs_touching); }},
    {"touching_share", "", "share of the cycles with some pair in contact",
     [](const SummaryCell& c, CsvLine& l) { l.Num("%.4g", c.row.touching_share); }},
    {"degraded_share", "", "share of the cycles in which the budget made some pair degrade",
     [](const SummaryCell& c, CsvLine& l) { l.Num("%.4g", c.row.degraded_share); }},
    {"max_force_N", "N", "largest |force on the tool|", [](const SummaryCell& c, CsvLine& l) { l.Num("%.6g", c.row.max_force); }},
    {"faults", "", "queries a pair's model refused", [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.faults); }},
    {"coherence_resets", "", "cycles the tool outran max_point_speed",
     [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.coherence_resets); }},
    {"max_displacement", "m", "largest displacement of any deformable body",
     [](const SummaryCell& c, CsvLine& l) { l.Num("%.6g", c.row.max_displacement); }},
    {"beyond_bound_cycles", "", "cycles some deformable body was past its deformation_bound",
     [](const SummaryCell& c, CsvLine& l) { l.Int(c.row.beyond_bound_cycles); }},
};

const ResultTable& CyclesTable() {
  static const ResultTable t = DeclareTable("world_cycles.csv", "one row per cycle per model: the tool's totals",
                                            TableKeys::kJobAndAllAxes, kCycleColumns);
  return t;
}
const ResultTable& PairsTable() {
  static const ResultTable t = DeclareTable("world_pairs.csv", "one row per near pair per cycle per model",
                                            TableKeys::kJobAndAllAxes, kPairColumns);
  return t;
}
const ResultTable& BodiesTable() {
  static const ResultTable t = DeclareTable("world_bodies.csv", "one row per deformable body per cycle per model",
                                            TableKeys::kJobAndAllAxes, kBodyColumns);
  return t;
}
const ResultTable& SummaryTable() {
  static const ResultTable t = DeclareTable("world_summary.csv", "one row per model per job", TableKeys::kJobAndAllAxes,
                                            kSummaryColumns);
  return t;
}

// The text of TABLE over every job's ROWS (a member of WorldJobResult).
template <class Row, std::size_t N>
std::string Csv(const ExperimentConfig& config, const std::vector<WorldJobResult>& results, const ResultTable& table,
                const TableColumn<Bound<Row>> (&columns)[N], std::vector<Row> WorldJobResult::*rows) {
  std::string out = table.Header(config);
  for (const WorldJobResult& r : results) {
    for (const Row& row : r.*rows) {
      CsvLine line(&out);
      table.AppendKeys(config, r.job, &line);
      AppendCells(columns, Bound<Row>{r, row}, &line);
      out += '\n';
    }
  }
  return out;
}

// The job's scene is one of many bodies (a scene axis may change it), the tool moves and the
// trajectory fits it; that every model takes every pair the parser checks for every study
// (CheckModelsAgainstScene).
void CheckWorldStudy(const ExperimentConfig& config, const ConfigNode& root, const Job& job) {
  const std::string where = config.file + (config.sweep.empty() ? std::string() : " (job " + job.Label() + ")");
  if (!job.scene.many_bodies()) {
    Fail(where, "study: many-bodies takes a scene of many bodies (tool: NAME, and pairs), but " + job.scene.file +
                    " has two bodies and no tool; study: contact compares models on it");
  }
  const std::string& tool = job.scene.bodies[std::size_t(job.scene.tool)].name;
  if (job.moving_body != tool) {
    root.Get("moving_body").Fail("in a scene of many bodies the tool moves: '" + tool + "'");
  }
  for (const auto& [axis, value] : job.axis_values) {
    if (axis == "roles") root.Get("sweep").Get("roles").Fail("exchanges two bodies' roles; a pair's roles follow from its model");
  }
  (void)WorldTrajectory(job);
}

void PrintSummary(const std::vector<WorldJobResult>& results) {
  std::printf("%-5s %-18s %6s %6s %8s %10s %10s %9s %9s %8s %11s\n", "job", "model", "bodies", "pairs", "cycles",
              "median us", "p99.9 us", "max|F| N", "near/cyc", "touching", "max disp mm");
  for (const WorldJobResult& r : results) {
    for (const WorldSummaryRow& s : r.summary) {
      std::printf("%-5d %-18s %6d %6d %8lld %10.1f %10.1f %9.4g %9.3g %8d %11.4g\n", r.job.index,
                  r.models[std::size_t(s.model)].c_str(), s.bodies, s.pairs, (long long)s.cycles, s.median_us,
                  s.p999_us, s.max_force, s.mean_pairs_near, s.max_pairs_touching, 1e3 * s.max_displacement);
    }
  }
}

void RunStudy(const ExperimentConfig& config, const RunOptions& options, const std::vector<int>& only) {
  const std::size_t total = JobCount(config);
  std::fprintf(stderr, "experiment %s (many-bodies study): %zu of %zu jobs\n", config.name.c_str(),
               only.empty() ? total : only.size(), total);
  PrintSummary(RunWorldStudy(config, options, only));
}

}  // namespace

WorldJobResult RunWorldJob(const Job& job, const RunOptions& options) {
  const Trajectory trajectory = MakeTrajectory(WorldTrajectory(job));
  WorldJobResult result;
  result.job = job;
  result.models = job.models;
  for (int m = 0; m < int(job.models.size()); ++m) RunModel(job, options, trajectory, m, &result);
  return result;
}

std::vector<WorldJobResult> RunWorldStudy(const ExperimentConfig& config, const RunOptions& options,
                                          const std::vector<int>& job_indices) {
  std::vector<WorldJobResult> results(job_indices.empty() ? JobCount(config) : job_indices.size());
  const JobsRun jobs = RunJobs(config, job_indices, options, [&](std::size_t i, const Job& job) {
    results[i] = RunWorldJob(job, options);
  });
  WriteStudyResults(StudyOf(config), options.out_dir,
                    {Csv(config, results, CyclesTable(), kCycleColumns, &WorldJobResult::cycles),
                     Csv(config, results, PairsTable(), kPairColumns, &WorldJobResult::pair_rows),
                     Csv(config, results, BodiesTable(), kBodyColumns, &WorldJobResult::body_rows),
                     Csv(config, results, SummaryTable(), kSummaryColumns, &WorldJobResult::summary)},
                    RunMetadata(config, jobs.indices, jobs.wall_seconds, jobs.parallel));
  return results;
}

void RegisterManyBodiesStudy() {
  Study s;
  s.name = "many-bodies";
  s.description = "a tool moved through a scene of many bodies: every pair, one budget, the deformable bodies stepped";
  s.sections = {
      {"models", "list of model names (default: the scene's)", "the model of the pairs without their own; one run each"},
      {"moving_body", "the tool's name (the default)", "the body the trajectory moves: in a scene of many bodies, its tool"},
      {"trajectory", "mapping (the trajectory reference; required)",
       "the tool's motion from its scene pose, cycle by cycle (a vector direction; no touch)"},
  };
  s.required = {"trajectory"};
  s.tables = {CyclesTable(), PairsTable(), BodiesTable(), SummaryTable()};
  s.many_bodies = true;
  s.replayable = true;  // world_cycles.csv: the tool's poses; world_bodies.csv: the deformable bodies' q
  s.timing = true;  // it measures the cycle's time: one job at a time
  s.check = CheckWorldStudy;
  s.run = RunStudy;
  RegisterStudy(std::move(s));
}

}  // namespace contactlab
