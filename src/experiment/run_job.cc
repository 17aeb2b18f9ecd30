// One job of an experiment: the moving body follows the trajectory cycle by cycle, every
// model of the job is evaluated at each pose (and the reference every reference_every
// cycles), and the per-cycle rows and per-model summary metrics are collected.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "contact/coherence_guard.h"
#include "experiment/contact_placement.h"
#include "experiment/metrics.h"
#include "experiment/runner.h"
#include "deform/body_dynamics.h"
#include "util/error.h"

namespace contactlab {
namespace {

// The trajectory of a job with a scalar "direction: toward" resolved to the unit vector from the
// moving body's start to the other body's origin.
ConfigNode ResolvedTrajectoryNode(const ConfigNode& trajectory, const Pose& X_moving0, const Pose& X_other0) {
  YAML::Node tyaml = YAML::Clone(trajectory.yaml());
  if (tyaml["direction"] && tyaml["direction"].IsScalar()) {
    const Eigen::Vector3d toward = (X_other0.translation - X_moving0.translation).normalized();
    tyaml["direction"] = std::vector<double>{toward.x(), toward.y(), toward.z()};
  }
  return ConfigNode(tyaml, std::make_shared<const std::string>(trajectory.file()), trajectory.path());
}

// The reference model of the job: the config's reference model on the same scene, or on a
// denser version of it (more points, levels or field resolution), always at full depth.
std::unique_ptr<ContactModel> MakeReference(const ExperimentConfig& config, const Scene& scene,
                                            const RunOptions& options, std::unique_ptr<SceneAssets>* assets) {
  if (config.reference_model.empty()) return nullptr;
  Scene ref_scene = scene;
  if (config.reference_points > 0) ref_scene.pointshell_body.pointshell.points = config.reference_points;
  if (config.reference_levels > 0) ref_scene.pointshell_body.pointshell.levels = config.reference_levels;
  if (config.reference_resolution > 0) ref_scene.field_body.field.resolution = config.reference_resolution;
  ref_scene.model.level = -1;
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

// Microseconds since T0.
double MicrosecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

// The median of V (reordered).
double Median(std::vector<double>* v) {
  std::nth_element(v->begin(), v->begin() + std::ptrdiff_t(v->size() / 2), v->end());
  return (*v)[v->size() / 2];
}

}  // namespace

JobResult RunJob(const ExperimentConfig& config, const Job& job, const RunOptions& options) {
  JobResult result;
  result.job = job;
  const Scene& scene = job.scene;
  SceneAssets assets(scene, options.assets);
  const bool moving_is_B = scene.field_body.name == job.moving_body;
  Pose X_WA0 = scene.pointshell_body.pose, X_WB0 = scene.field_body.pose;

  // The trajectory, and with touch: true the moving body moved along its direction until the
  // deepest point of the paper's model (linear, deepest level) is touch_depth deep.
  const TrajectorySpec spec = ParseTrajectorySpec(
      ResolvedTrajectoryNode(job.trajectory_node, moving_is_B ? X_WB0 : X_WA0, moving_is_B ? X_WA0 : X_WB0));
  const Trajectory trajectory = MakeTrajectory(spec);
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
      moved = TouchAlong(scene, assets, moving_is_B, X_WA0, X_WB0, dir, depth, where);
    } else {
      const Scene& normal = placement->scene;
      SceneAssets normal_assets(normal, options.assets);
      const bool normal_moving_is_B = normal.field_body.name == job.moving_body;
      moved = TouchAlong(normal, normal_assets, normal_moving_is_B, normal.pointshell_body.pose, normal.field_body.pose,
                         dir, depth, where + " (placed as job " + std::to_string(placement->index) + ")");
    }
    (moving_is_B ? X_WB0 : X_WA0) = moved;
  }
  const Pose start = moving_is_B ? X_WB0 : X_WA0;
  const double dt = scene.model.cycle_seconds;
  // Bounded before the per-cycle records are allocated.
  if (!(trajectory.duration() / dt <= kMaxTrajectorySamples)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "trajectory.duration: %.3g s at a cycle of %.3g s is %.3g cycles, more than the limit of %.0e",
                  trajectory.duration(), dt, trajectory.duration() / dt, kMaxTrajectorySamples);
    Fail(config.file, buf);
  }
  const std::int64_t cycles = std::int64_t(std::floor(trajectory.duration() / dt + 1e-9)) + 1;

  std::unique_ptr<SceneAssets> reference_assets;
  const std::unique_ptr<ContactModel> reference = MakeReference(config, scene, options, &reference_assets);
  // Every model follows the same poses: a reference that ignores deformation (all but a
  // deformable pointshell reference) is evaluated once per cycle and reused by each model.
  const ContactModelNeeds* reference_needs = reference ? &FindContactModel(config.reference_model)->needs : nullptr;
  const bool reuse_reference = reference_needs && !reference_needs->deformable_A && !reference_needs->deformable_B;
  // By cycle, when reused: filled by the first model.
  std::vector<std::optional<Eigen::Vector3d>> reference_at(reuse_reference ? std::size_t(cycles) : 0);

  // The deformable bodies' dynamics (paper sec. 4 and 5), from rest for each model.
  SceneDynamics dynamics = MakeSceneDynamics(assets, dt);
  // The guard of the models' temporal coherence, as in the haptic cycle: the moving body's
  // motion per cycle against the scene's max_point_speed.
  CoherenceGuard coherence(scene.model.max_point_speed, scene.model.cycle_seconds,
                           (moving_is_B ? assets.B : assets.A).mesh()->MaxVertexRadius(),
                           config.file + ": model.max_point_speed");
  const int r_A = dynamics.A ? dynamics.A->r() : 0;
  const int r_B = dynamics.B ? dynamics.B->r() : 0;
  // Everything the cycle rows hold, allocated here: the loop below records without allocating.
  const std::size_t total_rows = job.models.size() * std::size_t(cycles);
  auto storage = std::make_shared<CycleStorage>();
  storage->models = job.models;
  storage->q.resize(total_rows * std::size_t(r_A + r_B));
  result.storage = storage;
  result.cycles.reserve(total_rows);

  for (std::size_t m = 0; m < job.models.size(); ++m) {
    const std::string& name = storage->models[m];
    std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, scene, assets);
    // Depths in voxels only for models whose depth is measured on B's field grid.
    const bool in_voxels = FindContactModel(name)->needs.depth_in_field_voxels;
    const double spacing = in_voxels ? assets.B.field()->spacing() : 0.0;
    std::vector<Eigen::Vector3d> forces, refs;
    std::vector<Pose> poses;
    std::vector<bool> has_ref;
    std::vector<double> times;
    std::vector<int> levels;
    std::vector<double> step_times, step_times_B;
    for (auto* v : {&forces, &refs}) v->reserve(std::size_t(cycles));
    for (auto* v : {&times, &step_times, &step_times_B}) v->reserve(std::size_t(cycles));
    poses.reserve(std::size_t(cycles));
    has_ref.reserve(std::size_t(cycles));
    levels.reserve(std::size_t(cycles));
    double nodes_sum = 0, max_depth = 0;
    dynamics.Reset();
    double max_displacement = 0;
    std::int64_t contact_faults = 0;
    // The moving body follows the trajectory from its start pose; the other stays put.
    auto moving_pose = [&](std::int64_t k) {
      const Pose d = trajectory.At(trajectory.start_time() + double(k) * dt);
      return Pose{(d.rotation * start.rotation).normalized(), start.translation + d.translation};
    };
    coherence.Start(moving_pose(0));
    for (std::int64_t k = 0; k < cycles; ++k) {
      const Pose X_moving = moving_pose(k);
      // Faster than the coherence assumes: this cycle traverses in full, coherence restarts.
      if (coherence.Check(X_moving)) model->Reset();
      ContactQuery q;
      q.X_WA = moving_is_B ? X_WA0 : X_moving;
      q.X_WB = moving_is_B ? X_moving : X_WB0;
      q.cycle = k;
      q.node_budget = scene.node_budget;
      if (dynamics.A) q.deformation_A = dynamics.A->Prepare();
      if (dynamics.B) q.deformation_B = dynamics.B->Prepare();
      const auto t0 = std::chrono::steady_clock::now();
      const ContactResult r = model->Evaluate(q);
      const double us = MicrosecondsSince(t0);
      CycleRow row;
      row.job = job.index;
      row.model = name;
      row.cycle = k;
      row.t = double(k) * dt;
      row.position = X_moving.translation;
      row.rotation = X_moving.rotation;
      OnMovingBody(moving_is_B, q, r.on_B, &row.force, &row.torque);
      row.contacts = r.stats.points_in_contact;
      row.nodes = r.stats.nodes_visited;
      row.level = r.stats.level_rendered;
      row.max_penetration = r.stats.max_penetration;
      row.depth_voxels = spacing > 0 ? r.stats.max_penetration / spacing : 0.0;
      row.time_us = us;
      contact_faults += r.stats.faults > 0 ? 1 : 0;  // the model refused the query: no force
      if (reference && k % config.reference_every == 0) {
        if (reuse_reference && reference_at[std::size_t(k)]) {
          row.reference_force = *reference_at[std::size_t(k)];
        } else {
          Eigen::Vector3d T;
          // The reference sees the deformations and writes no reduced force.
          ContactQuery rq = q;
          rq.node_budget = 0;
          const BodyDeformation ref_A{q.deformation_A ? q.deformation_A->q : nullptr};
          const BodyDeformation ref_B{q.deformation_B ? q.deformation_B->q : nullptr};
          rq.deformation_A = q.deformation_A ? &ref_A : nullptr;
          rq.deformation_B = q.deformation_B ? &ref_B : nullptr;
          OnMovingBody(moving_is_B, rq, reference->Evaluate(rq).on_B, &row.reference_force, &T);
          if (reuse_reference) reference_at[std::size_t(k)] = row.reference_force;
        }
        row.has_reference = true;
      }
      // The deformations advance after the query, held fixed during it; the row keeps the
      // states after the steps in its slot of the storage.
      double* q_row = storage->q.data() + result.cycles.size() * std::size_t(r_A + r_B);
      if (dynamics.A) {
        const auto ts = std::chrono::steady_clock::now();
        dynamics.A->Step();
        RecordDeformation(*dynamics.A, false, MicrosecondsSince(ts), &row);
        step_times.push_back(row.step_us);
        std::copy_n(dynamics.A->state().q.data(), r_A, q_row);
        row.q = {q_row, std::size_t(r_A)};
      }
      if (dynamics.B) {
        const auto ts = std::chrono::steady_clock::now();
        dynamics.B->Step();
        RecordDeformation(*dynamics.B, true, MicrosecondsSince(ts), &row);
        step_times_B.push_back(row.step_B_us);
        std::copy_n(dynamics.B->state().q.data(), r_B, q_row + r_A);
        row.q_B = {q_row + r_A, std::size_t(r_B)};
      }
      max_displacement = std::max(max_displacement, row.max_displacement);
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
    const double force_scale = MedianForceInContact(forces);
    if (force_scale > 0) {
      s.max_jump_rel = c.max_jump / force_scale;
      s.lipschitz_rel = c.lipschitz / force_scale;
    }
    if (reference) {
      const ErrorMetrics e = ErrorAgainstReference(forces, refs, has_ref);
      s.rms_rel_error = e.rms_relative;
      s.max_dir_error_deg = e.max_direction_deg;
      s.median_dir_error_deg = e.median_direction_deg;
      s.p95_dir_error_deg = e.p95_direction_deg;
      if (std::isfinite(e.scale)) {
        s.ref_scale = e.scale;
        s.rms_rel_error_calibrated = e.rms_relative_calibrated;
      }
    }
    for (const Eigen::Vector3d& f : forces) {
      s.max_force = std::max(s.max_force, f.norm());
      s.mean_force += f.norm() / double(cycles);
    }
    s.max_depth_voxels = max_depth;
    s.coherence_resets = coherence.resets();
    s.contact_faults = contact_faults;
    if (dynamics.A) {
      s.modes = r_A;
      s.median_step_us = Median(&step_times);
    }
    if (dynamics.B) {
      s.modes_B = r_B;
      s.median_step_B_us = Median(&step_times_B);
    }
    if (dynamics.any()) s.max_displacement = max_displacement;
    // The memory of the body data this model reads, from the loaded arrays.
    const ContactModelNeeds& needs = FindContactModel(name)->needs;
    if (needs.field_B) s.field_B_bytes = assets.B.field()->memory_bytes();
    if (needs.pointshell_A) s.pointshell_A_bytes = assets.A.pointshell()->memory_bytes();
    result.summary.push_back(s);
  }
  return result;
}

}  // namespace contactlab
