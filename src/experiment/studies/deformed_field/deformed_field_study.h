// The deformed-field study (`study: deformed-field` in an experiment config; Barbič & James
// 2008, sec. 4.2, Fig. 10): per job, the scene's field body (deformable) is posed by point
// loads pulling parts apart, and its deformed distance field (proxies, k, domains from the
// job's scene) is compared with the exact distance to the deformed surface mesh: RMS and
// largest error in the contact band, the spurious inside volume (mirroring), and the measured
// time of one query. Selected jobs also write a slice of both fields for isocontour plots.
//
//   study: deformed-field
//   scene: scenes/armadillo-legs.yaml          # its field body must be deformable
//   deformation:
//     loads:                                   # material points (body frame, metres) and
//       - {at: [-0.03, -0.08, -0.016], force: [-1, 0, 0]}   # force directions; scaled together
//       - {at: [0.04, -0.08, -0.018], force: [1, 0, 0]}
//     max_displacement: 0.10                   # largest surface displacement / body size
//   measure:
//     band_cells: 2                            # the contact band |d| <= band_cells rest-field cells
//     points: 2000                             # band points per job
//     seed: 1
//     timing_repeats: 5                        # the query time is the median over these passes
//     slice: {axis: z, at: -0.016, resolution: 200, window: [-0.1, -0.13, 0.1, 0],  # default: the body
//             jobs: {proxies: 40, neighbours: 5, domains: [1, legs]}}
//   sweep:
//     proxies: [20, 40, 80]
//     neighbours: [3, 5, 8]
//     domains: [1, 3, {label: legs, value: [{halfspace: [1, 0, 0, 0.007]}, {halfspace: [-1, 0, 0, -0.007]}]}]
//
// Outputs: field_error.csv (one row per job) and field_slice.csv (exact and approximate
// distance on the slice's grid, for the jobs whose sweep values match slice.jobs; all jobs when
// it is absent), both written atomically with meta.json.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "deform/deformed_field_accuracy.h"
#include "experiment/runner.h"

namespace contactlab {

struct FieldStudySpec {
  std::vector<PointLoad> loads;
  std::vector<std::string> load_where;  // "FILE:LINE: deformation.loads[i]" for errors
  double max_displacement = 0.10;       // fraction of the body's size (largest bounding-box side)
  double band_cells = 2;
  int points = 2000;
  std::uint64_t seed = 1;
  int timing_repeats = 5;
  bool slice = false;                   // measure.slice given
  int slice_axis = 2;                   // the plane's normal axis (0 x, 1 y, 2 z)
  double slice_at = 0;                  // its coordinate, metres, body frame
  int slice_resolution = 200;           // grid points along the plane's longer side
  bool slice_window = false;            // window given: [lo_b, lo_c, hi_b, hi_c] on the plane's
  Eigen::Vector4d window = Eigen::Vector4d::Zero();  // axes (x, y for z; x, z for y; y, z for x), m
  // (axis, values): a job writes the slice when its value of every such axis is one of these.
  std::vector<std::pair<std::string, std::vector<std::string>>> slice_jobs;
};

// Reads the study's sections of a job's config document ROOT (deformation, measure). Throws
// Error naming the file, line and key.
FieldStudySpec ParseFieldStudySpec(const ConfigNode& root);

// One job's numbers.
struct FieldErrorRow {
  int proxies = 0, neighbours = 0, domains = 0, slots = 0, r = 0;
  bool explicit_domains = false;    // user-given regions, not automatic clusters
  double cell = 0;                  // rest-field spacing, m
  double body_size = 0;             // largest side of the rest mesh's bounding box, m
  double max_displacement = 0;      // m, largest surface displacement of the pose
  int points = 0;                   // band points
  double rms = 0, max = 0, mean = 0;  // approximate - exact in the band, m
  double false_inside_volume = 0;   // m^3 (deform/deformed_field_accuracy.h)
  double query_ns = 0;              // one DeformedDistanceField::Distance, median of the passes
  double update_ns = 0;             // one DeformedFieldState::Update
  double exact_ns = 0;              // one exact reference distance (BVH + pseudo-normal)
};

struct FieldSliceRow {
  int i = 0, j = 0;                 // grid indices along the plane's first and second axes
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  // body frame, m
  double exact = 0, approx = 0;     // m
};

struct FieldJobResult {
  Job job;
  FieldErrorRow error;
  std::vector<FieldSliceRow> slice;
};

// Runs JOB of a deformed-field CONFIG (assets through OPTIONS.assets).
FieldJobResult RunDeformedFieldJob(const ExperimentConfig& config, const Job& job, const RunOptions& options);

// Runs JOBS (all when empty), one at a time unless OPTIONS says otherwise, and writes
// field_error.csv, field_slice.csv and meta.json into OPTIONS.out_dir. The study registers as
// `deformed-field` (experiment/study.h).
std::vector<FieldErrorRow> RunDeformedFieldStudy(const ExperimentConfig& config, const RunOptions& options,
                                                 const std::vector<int>& jobs = {});

}  // namespace contactlab
