// One job of an experiment: the moving body follows the trajectory cycle by cycle, every
// model of the job is evaluated at each pose (and the reference every reference_every
// cycles), and the per-cycle rows and per-model summary metrics are collected.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "contact/coherence_guard.h"
#include "contact/scaled_contact_model.h"
#include "contact/volume_fill.h"
#include "deform/body_dynamics.h"
#include "scene/contact_placement.h"
#include "scene/scene_query.h"
#include "experiment/studies/contact/contact_study.h"
#include "experiment/studies/contact/metrics.h"
#include "contact/model_registry.h"
#include "haptics/contact_cycle.h"
#include "util/error.h"

namespace contactlab {
namespace {

// The reference model of the job: the config's reference model on the same scene, or on a
// denser version of it (more points, levels or field resolution), always at full depth.
std::unique_ptr<ContactModel> MakeReference(const ExperimentConfig& config, const Scene& scene,
                                            const RunOptions& options, std::unique_ptr<SceneAssets>* assets) {
  if (config.reference_model.empty()) return nullptr;
  Scene ref_scene = scene;
  if (config.reference_points > 0) ref_scene.pointshell_body.pointshell.points = config.reference_points;
  if (config.reference_levels > 0) ref_scene.pointshell_body.pointshell.levels = config.reference_levels;
  if (config.reference_resolution > 0) ref_scene.field_body.field.resolution = config.reference_resolution;
  // The reference at its most detail, as its registry entry says (the paper's model: its deepest level).
  if (const ContactModelEntry* e = FindContactModel(config.reference_model); e != nullptr && e->at_full_detail) {
    e->at_full_detail(ref_scene.model_params);
  }
  ref_scene.node_budget = 0;
  *assets = std::make_unique<SceneAssets>(ref_scene, options.assets);
  return MakeSceneContactModel(config.reference_model, ref_scene, **assets);
}

// Wrench on the moving body about its own origin, from the wrench on B of query Q.
void OnMovingBody(bool moving_is_B, const ContactQuery& q, const Wrench& on_B, Eigen::Vector3d* F, Eigen::Vector3d* T) {
  if (moving_is_B) {
    *F = on_B.force;
    *T = on_B.torque;
  } else {
    *F = -on_B.force;
    *T = -on_B.torque - (q.X_WB.translation - q.X_WA.translation).cross(on_B.force);
  }
}

// Adds the state of DYNAMICS after this cycle's step to ROW: the step time (US) in the body's own
// column (IS_B), energies summed and the largest displacement over both bodies.
void RecordDeformation(BodyDynamics& dynamics, bool is_B, double us, CycleRow* row) {
  (is_B ? row->step_B_us : row->step_us) = us;
  row->deformable = true;
  row->elastic_energy += dynamics.PotentialEnergy();
  row->kinetic_energy += dynamics.KineticEnergy();
  row->max_displacement = std::max(row->max_displacement, dynamics.MaxDisplacement());
}

// The median of V (reordered).
double Median(std::vector<double>* v) {
  std::nth_element(v->begin(), v->begin() + std::ptrdiff_t(v->size() / 2), v->end());
  return (*v)[v->size() / 2];
}

// How the job's moving body moves: the bodies' start poses (the moving one placed touching when
// the trajectory says touch: true), the trajectory and the cycles it takes.
struct JobMotion {
  explicit JobMotion(Trajectory t) : trajectory(std::move(t)) {}
  bool moving_is_B = false;
  Pose X_WA0, X_WB0;  // the bodies at the start (the moving one placed)
  Pose start;         // the moving body's start pose
  Trajectory trajectory;
  double dt = 1e-3;
  std::int64_t cycles = 0;

  // The moving body at cycle K: the trajectory applied to its start pose.
  Pose At(std::int64_t k) const {
    const Pose d = trajectory.At(trajectory.start_time() + double(k) * dt);
    return Pose{(d.rotation * start.rotation).normalized(), start.translation + d.translation};
  }
};

// The trajectory of JOB, and with touch: true the moving body moved along its direction until
// the deepest point of the paper's model (linear, deepest level) is touch_depth deep. Throws
// Error naming the config when the trajectory needs more cycles than the limit.
JobMotion PlanMotion(const ExperimentConfig& config, const Job& job, SceneAssets& assets, const RunOptions& options) {
  const Scene& scene = job.scene;
  const bool moving_is_B = scene.field_body.name == job.moving_body;
  const Pose& X_moving0 = moving_is_B ? scene.field_body.pose : scene.pointshell_body.pose;
  const Pose& X_other0 = moving_is_B ? scene.pointshell_body.pose : scene.field_body.pose;
  TrajectorySpec spec = *job.trajectory;
  // direction: toward, the unit vector from the moving body's start to the other body's origin.
  if (spec.toward) spec.shape.direction = (X_other0.translation - X_moving0.translation).normalized();
  JobMotion m(MakeTrajectory(spec));
  m.moving_is_B = moving_is_B;
  m.X_WA0 = scene.pointshell_body.pose;
  m.X_WB0 = scene.field_body.pose;
  if (spec.touch) {
    const Eigen::Vector3d dir = spec.shape.direction.normalized();
    const double depth = spec.touch_depth;
    const std::string where = config.file + ": job " + std::to_string(job.index);
    // Both role orders follow one motion: a job whose roles were swapped takes the placement of
    // the job with the same sweep values in the config's role order (the same poses, the same
    // field resolutions on the same bodies), so role reversal compares like with like.
    const std::optional<Job> placement = job.roles_swapped ? ConfigRoleOrderJob(config, job) : std::nullopt;
    Pose moved;
    if (!placement) {
      moved = TouchAlong(scene, assets, m.moving_is_B, m.X_WA0, m.X_WB0, dir, depth, where);
    } else {
      const Scene& normal = placement->scene;
      SceneAssets normal_assets(normal, options.assets);
      const bool normal_moving_is_B = normal.field_body.name == job.moving_body;
      moved = TouchAlong(normal, normal_assets, normal_moving_is_B, normal.pointshell_body.pose, normal.field_body.pose,
                         dir, depth, where + " (placed as job " + std::to_string(placement->index) + ")");
    }
    (m.moving_is_B ? m.X_WB0 : m.X_WA0) = moved;
  }
  m.start = m.moving_is_B ? m.X_WB0 : m.X_WA0;
  m.dt = scene.model.cycle_seconds;
  // Bounded before the per-cycle records are allocated.
  if (!(m.trajectory.duration() / m.dt <= kMaxTrajectorySamples)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "trajectory.duration: %.3g s at a cycle of %.3g s is %.3g cycles, more than the limit of %.0e",
                  m.trajectory.duration(), m.dt, m.trajectory.duration() / m.dt, kMaxTrajectorySamples);
    Fail(config.file, buf);
  }
  m.cycles = std::int64_t(std::floor(m.trajectory.duration() / m.dt + 1e-9)) + 1;
  return m;
}

// The config's reference model on the job's scene (or a denser version of it), evaluated every
// reference_every cycles. Every model follows the same poses: a reference that ignores
// deformation (all but a deformable pointshell reference) is evaluated once per cycle, by the
// first model's run, and reused by the others.
class JobReference {
 public:
  JobReference(const ExperimentConfig& config, const Scene& scene, const RunOptions& options, std::int64_t cycles)
      : every_(config.reference_every), model_(MakeReference(config, scene, options, &assets_)) {
    if (!model_) return;
    const ContactModelNeeds& needs = FindContactModel(config.reference_model)->needs;
    if (!needs.deformable_A && !needs.deformable_B) at_.resize(std::size_t(cycles));
  }
  explicit operator bool() const { return model_ != nullptr; }
  bool Due(std::int64_t k) const { return model_ && k % every_ == 0; }

  // The reference force on the moving body at cycle K, where the model's query was Q.
  Eigen::Vector3d Force(std::int64_t k, const ContactQuery& q, bool moving_is_B) {
    const bool reuse = !at_.empty();
    if (reuse && at_[std::size_t(k)]) return *at_[std::size_t(k)];
    // The reference sees the deformations and writes no reduced force.
    ContactQuery rq = q;
    rq.node_budget = 0;
    const BodyDeformation ref_A{q.deformation_A ? q.deformation_A->q : nullptr};
    const BodyDeformation ref_B{q.deformation_B ? q.deformation_B->q : nullptr};
    rq.deformation_A = q.deformation_A ? &ref_A : nullptr;
    rq.deformation_B = q.deformation_B ? &ref_B : nullptr;
    Eigen::Vector3d F, T;
    OnMovingBody(moving_is_B, rq, model_->Evaluate(rq).on_B, &F, &T);
    if (reuse) at_[std::size_t(k)] = F;
    return F;
  }

 private:
  std::int64_t every_;
  std::unique_ptr<SceneAssets> assets_;
  std::unique_ptr<ContactModel> model_;
  std::vector<std::optional<Eigen::Vector3d>> at_;  // by cycle, when reused
};

// What one model's run keeps beyond its rows, for its summary; sized before the first cycle.
struct ModelTrace {
  std::vector<Eigen::Vector3d> forces, refs;
  std::vector<Pose> poses;
  std::vector<bool> has_ref;
  std::vector<double> times, step_times, step_times_B;
  std::vector<int> levels;
  double nodes_sum = 0, max_depth = 0, max_displacement = 0;
  std::int64_t degraded_cycles = 0;
  std::int64_t contact_faults = 0;
  double wrench_scale = 1;  // model.stiffness: matched's factor (1: the model's own stiffness)
  double fill_A = -1, fill_B = -1;  // contact/volume_fill.h (-1: the model fills no volume)

  explicit ModelTrace(std::int64_t cycles) {
    const std::size_t n = std::size_t(cycles);
    for (auto* v : {&forces, &refs}) v->reserve(n);
    for (auto* v : {&times, &step_times, &step_times_B}) v->reserve(n);
    poses.reserve(n);
    has_ref.reserve(n);
    levels.reserve(n);
  }
  void Add(const CycleRow& row, const Pose& X_moving) {
    max_displacement = std::max(max_displacement, row.max_displacement);
    forces.push_back(row.force);
    refs.push_back(row.reference_force);
    has_ref.push_back(row.has_reference);
    poses.push_back(X_moving);
    times.push_back(row.time_us);
    levels.push_back(row.level);
    nodes_sum += double(row.nodes);
    if (row.degraded > 0) ++degraded_cycles;
    max_depth = std::max(max_depth, row.depth_voxels);
  }
};

// The job's fixed parts every model's run reads.
struct JobSetup {
  const ExperimentConfig& config;
  const Job& job;
  SceneAssets& assets;
  const JobMotion& motion;
  JobReference& reference;
  SceneDynamics& dynamics;
  CoherenceGuard& coherence;
};

// Steps the deformable bodies of CYCLE at the end of a cycle (their deformation held fixed during
// its query) and records them into ROW, their q in Q_ROW (the row's slot of the storage).
void StepBodies(ContactCycle& cycle, double* q_row, CycleRow* row, ModelTrace* trace) {
  BodyDynamics* A = cycle.dynamics_A();
  BodyDynamics* B = cycle.dynamics_B();
  const int r_A = A ? A->r() : 0;
  const int r_B = B ? B->r() : 0;
  const ContactCycleSteps steps = cycle.StepDeformations();
  if (A) {
    RecordDeformation(*A, false, 1e-3 * double(steps.step_A_ns), row);
    trace->step_times.push_back(row->step_us);
    std::copy_n(A->state().q.data(), r_A, q_row);
    row->q = {q_row, std::size_t(r_A)};
  }
  if (B) {
    RecordDeformation(*B, true, 1e-3 * double(steps.step_B_ns), row);
    trace->step_times_B.push_back(row->step_B_us);
    std::copy_n(B->state().q.data(), r_B, q_row + r_A);
    row->q_B = {q_row + r_A, std::size_t(r_B)};
  }
}

// The row of cycle K of model NAME: the moving body at X_MOVING, the model's result R of query Q,
// its depth in cells of SPACING (0: not measured on B's grid).
CycleRow MakeCycleRow(const JobSetup& setup, const std::string& name, std::int64_t k, const Pose& X_moving,
                      const ContactQuery& q, const ContactResult& r, double spacing) {
  CycleRow row;
  row.job = setup.job.index;
  row.model = name;
  row.cycle = k;
  row.t = double(k) * setup.motion.dt;
  row.position = X_moving.translation;
  row.rotation = X_moving.rotation;
  OnMovingBody(setup.motion.moving_is_B, q, r.on_B, &row.force, &row.torque);
  row.contacts = r.stats.points_in_contact;
  row.nodes = r.stats.nodes_visited;
  row.level = r.stats.level_rendered;
  row.max_penetration = r.stats.max_penetration;
  row.depth_voxels = spacing > 0 ? r.stats.max_penetration / spacing : 0.0;
  row.contact_area = r.stats.contact_area;
  row.patches = r.stats.patches;
  row.degraded = r.stats.degraded;
  return row;
}

// Model NAME along the job's motion, cycle by cycle (the cycle sequence of the haptic loop,
// haptics/contact_cycle.h): its rows appended to RESULT (viewing STORAGE, allocated before:
// recording allocates nothing), what its summary needs in TRACE.
void RunModel(const JobSetup& setup, const std::string& name, CycleStorage& storage, JobResult* result,
              ModelTrace* trace) {
  const Scene& scene = setup.job.scene;
  const JobMotion& motion = setup.motion;
  SceneDynamics& dynamics = setup.dynamics;
  std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, scene, setup.assets);
  trace->wrench_scale = WrenchScaleOf(*model);
  if (const auto* fill = dynamic_cast<const VolumeFill*>(&UnscaledOf(*model))) {
    trace->fill_A = fill->fill_A();
    trace->fill_B = fill->fill_B();
  }
  // Depths in voxels only for models whose depth is measured on B's field grid.
  const double spacing =
      FindContactModel(name)->needs.depth_in_field_voxels ? setup.assets.B.field()->spacing() : 0.0;
  const std::size_t q_stride = std::size_t((dynamics.A ? dynamics.A->r() : 0) + (dynamics.B ? dynamics.B->r() : 0));
  ContactCycle cycle(model.get(), dynamics.A.get(), dynamics.B.get(), &setup.coherence);
  cycle.Start(motion.At(0));
  for (std::int64_t k = 0; k < motion.cycles; ++k) {
    // The query at the moving body's pose: faster than the coherence assumes, this cycle
    // traverses in full; a deformation a step left non-finite (diverged) is not queried.
    const Pose X_moving = motion.At(k);
    ContactQuery q = SceneContactQuery(scene, motion.moving_is_B ? motion.X_WA0 : X_moving,
                                       motion.moving_is_B ? X_moving : motion.X_WB0, k);
    ContactCycleQuery done;
    const ContactResult r = cycle.Evaluate(X_moving, &q, &done);
    CycleRow row = MakeCycleRow(setup, name, k, X_moving, q, r, spacing);
    row.time_us = 1e-3 * double(done.query_ns);
    trace->contact_faults += r.stats.faults > 0 ? 1 : 0;  // the model refused the query: no force
    if (setup.reference.Due(k)) {
      row.reference_force = setup.reference.Force(k, q, motion.moving_is_B);
      row.has_reference = true;
    }
    StepBodies(cycle, storage.q.data() + result->cycles.size() * q_stride, &row, trace);
    trace->Add(row, X_moving);
    result->cycles.push_back(row);
  }
}

// Model NAME's metrics over the job's trajectory, from its TRACE.
SummaryRow Summarize(const JobSetup& setup, const std::string& name, ModelTrace& trace) {
  const Scene& scene = setup.job.scene;
  const std::int64_t cycles = setup.motion.cycles;
  SceneDynamics& dynamics = setup.dynamics;
  SummaryRow s;
  s.job = setup.job.index;
  s.model = name;
  s.points = scene.pointshell_body.pointshell.points;
  s.cycles = cycles;
  s.wrench_scale = trace.wrench_scale;
  const double radius = setup.assets.A.mesh()->Bounds().size().norm() / 2;
  const ContinuityMetrics c =
      ForceContinuity(trace.forces, trace.poses, setup.motion.dt, radius, setup.config.cutoff_hz);
  s.max_jump = c.max_jump;
  s.lipschitz = c.lipschitz;
  s.hf_share = c.high_frequency_share;
  const TimingMetrics t = Timing(trace.times, trace.levels, setup.motion.dt);
  s.median_us = t.median_us;
  s.p99_us = t.p99_us;
  s.max_us = t.max_us;
  s.level_switches_per_s = t.level_switches_per_second;
  s.mean_nodes = trace.nodes_sum / double(cycles);
  s.degraded_share = double(trace.degraded_cycles) / double(cycles);
  const double force_scale = MedianForceInContact(trace.forces);
  if (force_scale > 0) {
    s.max_jump_rel = c.max_jump / force_scale;
    s.lipschitz_rel = c.lipschitz / force_scale;
  }
  if (setup.reference) {
    const ErrorMetrics e = ErrorAgainstReference(trace.forces, trace.refs, trace.has_ref);
    s.rms_rel_error = e.rms_relative;
    s.max_dir_error_deg = e.max_direction_deg;
    s.median_dir_error_deg = e.median_direction_deg;
    s.p95_dir_error_deg = e.p95_direction_deg;
    if (std::isfinite(e.scale)) {
      s.ref_scale = e.scale;
      s.rms_rel_error_calibrated = e.rms_relative_calibrated;
    }
  }
  for (const Eigen::Vector3d& f : trace.forces) {
    s.max_force = std::max(s.max_force, f.norm());
    s.mean_force += f.norm() / double(cycles);
  }
  s.max_depth_voxels = trace.max_depth;
  s.fill_A = trace.fill_A;
  s.fill_B = trace.fill_B;
  s.coherence_resets = setup.coherence.resets();
  s.contact_faults = trace.contact_faults;
  if (dynamics.A) {
    s.modes = dynamics.A->r();
    s.median_step_us = Median(&trace.step_times);
  }
  if (dynamics.B) {
    s.modes_B = dynamics.B->r();
    s.median_step_B_us = Median(&trace.step_times_B);
  }
  if (dynamics.any()) s.max_displacement = trace.max_displacement;
  // The memory of the body data this model reads, from the loaded arrays.
  const ContactModelNeeds& needs = FindContactModel(name)->needs;
  if (needs.field_B) s.field_B_bytes = setup.assets.B.field()->memory_bytes();
  if (needs.pointshell_A) s.pointshell_A_bytes = setup.assets.A.pointshell()->memory_bytes();
  return s;
}

}  // namespace

JobResult RunJob(const ExperimentConfig& config, const Job& job, const RunOptions& options) {
  const Scene& scene = job.scene;
  SceneAssets assets(scene, options.assets);
  const JobMotion motion = PlanMotion(config, job, assets, options);
  JobReference reference(config, scene, options, motion.cycles);
  // The deformable bodies' dynamics (paper sec. 4 and 5), from rest for each model.
  SceneDynamics dynamics = MakeSceneDynamics(assets, motion.dt);
  // The guard of the models' temporal coherence, as in the haptic cycle: the moving body's
  // motion per cycle against the scene's max_point_speed.
  CoherenceGuard coherence(scene.model.max_point_speed, scene.model.cycle_seconds,
                           (motion.moving_is_B ? assets.B : assets.A).mesh()->MaxVertexRadius(),
                           config.file + ": model.max_point_speed");
  const JobSetup setup{config, job, assets, motion, reference, dynamics, coherence};

  // Everything the cycle rows hold, allocated here: the runs below record without allocating.
  JobResult result;
  result.job = job;
  const std::size_t total_rows = job.models.size() * std::size_t(motion.cycles);
  const int r = (dynamics.A ? dynamics.A->r() : 0) + (dynamics.B ? dynamics.B->r() : 0);
  auto storage = std::make_shared<CycleStorage>();
  storage->models = job.models;
  storage->q.resize(total_rows * std::size_t(r));
  result.storage = storage;
  result.cycles.reserve(total_rows);
  for (const std::string& name : storage->models) {
    ModelTrace trace(motion.cycles);
    RunModel(setup, name, *storage, &result, &trace);
    result.summary.push_back(Summarize(setup, name, trace));
  }
  return result;
}

}  // namespace contactlab
