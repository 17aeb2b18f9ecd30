// The contact study (`study: contact`, the default; registered in contact_study.cc): each model
// of a job follows the trajectory cycle by cycle; per-cycle rows and per-model summaries are
// collected, then written as long-format CSV (result_csv.h) with convergence.csv
// (convergence_table.h) and meta.json. One job's work is in run_job.cc.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "experiment/experiment_config.h"
#include "experiment/runner.h"

namespace contactlab {

// The study this runner runs (experiment/study.h; registered in contact_study.cc).
inline constexpr char kContactStudy[] = "contact";

// One row per cycle per model. Its model name and reduced coordinates view the storage of the
// JobResult that holds it (JobResult::storage, shared by the result's copies), so recording a
// row allocates nothing: a row is valid while that result, or a copy of it, lives.
struct CycleRow {
  int job = 0;
  std::string_view model;
  std::int64_t cycle = 0;
  double t = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // moving body origin, world
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // moving body orientation, world
  Eigen::Vector3d force = Eigen::Vector3d::Zero();     // on the moving body, world, N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();    // on the moving body about its origin, N m
  int contacts = 0;
  std::int64_t nodes = 0;
  int level = -1;
  double max_penetration = 0;   // m
  double depth_voxels = 0;      // max_penetration / spacing of the field body's field (pointshell models)
  double contact_area = 0;      // m^2, models with a contact surface (pressure-field)
  int patches = 0;              // its connected pieces
  int degraded = 0;             // steps the budget made the model degrade (ContactStats)
  double time_us = 0;
  bool has_reference = false;
  Eigen::Vector3d reference_force = Eigen::Vector3d::Zero();
  // Deformable bodies (paper sec. 4): their state after this cycle's steps.
  bool deformable = false;       // A or B deforms
  double step_us = 0;            // A's reduced integrator step, after the contact query
  double step_B_us = 0;          // B's (a deformed distance field body)
  double elastic_energy = 0;     // J, both bodies (mass-normalised coordinates: kg m^2 / s^2)
  double kinetic_energy = 0;     // J, both bodies
  double max_displacement = 0;   // m, largest |U q| over the simulation meshes' vertices
  std::span<const double> q;     // A's q_1 .. q_r after this cycle's step (empty: A is rigid)
  std::span<const double> q_B;   // B's
};

// Metrics of one model over one job's trajectory.
struct SummaryRow {
  int job = 0;
  std::string model;
  int points = 0;               // pointshell points of body A
  std::int64_t cycles = 0;
  double max_jump = 0, lipschitz = 0, hf_share = 0;
  double median_us = 0, p99_us = 0, max_us = 0, mean_nodes = 0, level_switches_per_s = 0;
  double degraded_share = 0;  // share of the cycles the budget made the model degrade
  double rms_rel_error = -1, max_dir_error_deg = -1;  // -1: no reference
  // Against the reference (metrics.h, ErrorAgainstReference; -1: no reference or no force):
  // the fitted stiffness scale, the relative RMS error after it, direction error quantiles.
  double ref_scale = -1, rms_rel_error_calibrated = -1;
  double median_dir_error_deg = -1, p95_dir_error_deg = -1;
  // Continuity relative to the force scale: max_jump and lipschitz over the median |F| in
  // contact (0 when the run had no force).
  double max_jump_rel = 0, lipschitz_rel = 0;
  double max_force = 0, mean_force = 0;
  double wrench_scale = 1;  // model.stiffness: matched's factor on the model's wrench (1: own)
  double max_depth_voxels = 0;
  // Cycles where the moving body outran the scene's max_point_speed, each resetting the model
  // (as the haptic cycle's coherence guard does); cycles whose query the model refused (no
  // force: ContactStats::faults, a deformation of the wrong size).
  std::int64_t coherence_resets = 0, contact_faults = 0;
  int modes = 0;                // r of a deformable pointshell body A, 0 when rigid
  double median_step_us = 0;    // A's reduced integrator step
  int modes_B = 0;              // r of a deformable field body B, 0 when rigid
  double median_step_B_us = 0;  // B's reduced integrator step
  double max_displacement = 0;  // m, over the trajectory (deformable bodies)
  // Memory of the body data the model reads (DistanceField and Pointshell memory_bytes); -1 when the
  // model does not read it: B's distance field and A's pointshell (points, normals, tree).
  std::int64_t field_B_bytes = -1, pointshell_A_bytes = -1;
  // The fraction of A's and of B's volume the model's filling covers (contact/volume_fill.h,
  // the inner spheres' packings); -1 when it fills none.
  double fill_A = -1, fill_B = -1;
  // The model reads A's pointshell, so POINTS means something for it (summary.csv, run table).
  bool reads_pointshell() const { return pointshell_A_bytes >= 0; }
};

// What the cycle rows of a job view, allocated once before its first cycle.
struct CycleStorage {
  std::vector<std::string> models;  // the job's model names
  std::vector<double> q;            // #rows x (r_A + r_B): each row's q, then its q_B
};

struct JobResult {
  Job job;
  std::vector<CycleRow> cycles;
  std::vector<SummaryRow> summary;
  std::shared_ptr<const CycleStorage> storage;  // what the rows of `cycles` view
};

// Runs JOB of CONFIG (assets built or reused through OPTIONS.assets).
JobResult RunJob(const ExperimentConfig& config, const Job& job, const RunOptions& options);

// Runs JOBS (all of them when empty) and writes cycles.csv, summary.csv, convergence.csv and
// meta.json into OPTIONS.out_dir. Returns the summary rows.
std::vector<SummaryRow> RunExperiment(const ExperimentConfig& config, const RunOptions& options,
                                      const std::vector<int>& jobs = {});

}  // namespace contactlab
