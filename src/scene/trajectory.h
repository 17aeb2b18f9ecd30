// Trajectories of the haptic body for experiments: procedural (approach and press, slide,
// twist, scan across bumps, circle) or recorded (CSV of t, x, y, z, qw, qx, qy, qz at 1 kHz,
// as a live session logs). A trajectory gives the pose of one body relative to its start
// pose at any time; poses between recorded samples are interpolated (slerp for rotation).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/pose.h"
#include "util/config_node.h"

namespace contactlab {

class Trajectory {
 public:
  // Samples (t, pose) with strictly increasing t (seconds).
  Trajectory(std::vector<double> times, std::vector<Pose> poses, std::string description);

  double duration() const { return times_.back() - times_.front(); }
  double start_time() const { return times_.front(); }
  // Pose at time T (clamped to the ends), interpolated between samples.
  Pose At(double t) const;
  const std::string& description() const { return description_; }
  std::size_t num_samples() const { return times_.size(); }
  // Largest speed of any point within RADIUS of the moving frame's origin, m/s (finite
  // differences over the samples): the bound temporal coherence needs.
  double MaxPointSpeed(double radius) const;

 private:
  std::vector<double> times_;
  std::vector<Pose> poses_;
  std::string description_;
};

// Procedural trajectories, as displacements from the start pose (translation in the world
// frame, rotation about the moving body's origin):
//  approach-press: along DIRECTION from -approach to +depth and back (smoothstep ramps);
//  slide:          press to DEPTH, then slide LENGTH along a tangent, and back;
//  twist:          press to DEPTH, then rotate by ANGLE about DIRECTION, and back;
//  scan:           press to DEPTH, then sweep LENGTH along the tangent at constant speed;
//  circle:         press to DEPTH, then a circle of RADIUS in the tangent plane;
//  pass:           along DIRECTION from -approach to +depth at constant SPEED, once (through a
//                  body at a set speed: the tunnelling study).
// At most 1e8 samples (cycles: a 27-hour run at 1 kHz) in a procedural trajectory.
inline constexpr double kMaxTrajectorySamples = 1e8;

struct ProceduralTrajectorySpec {
  std::string type = "approach-press";
  Eigen::Vector3d direction = Eigen::Vector3d(0, 0, -1);  // pressing direction (world)
  Eigen::Vector3d tangent = Eigen::Vector3d(1, 0, 0);     // slide/scan direction (made orthogonal)
  double approach = 0.005;  // m travelled before touching (start offset against the direction)
  double depth = 0.002;     // m of travel past the start pose
  double length = 0.02;     // m (slide, scan)
  double radius = 0.005;    // m (circle)
  double angle = 0.5;       // rad (twist)
  double speed = 1.0;       // m/s (pass; its duration is (approach + depth) / speed)
  double duration = 2.0;    // s
  double rate = 1000;       // samples per second
};
Trajectory MakeProceduralTrajectory(const ProceduralTrajectorySpec& spec);

// Reads a recorded trajectory (geometry/pose_samples_csv.h; session logs replay directly),
// relative to its first sample. Throws Error naming the file and line for bad rows, and the
// file when it holds fewer than two rows.
Trajectory LoadTrajectoryCsv(const std::filesystem::path& file);

// Writes t,x,y,z,qw,qx,qy,qz at RATE samples per second, atomically.
void SaveTrajectoryCsv(const Trajectory& trajectory, const std::filesystem::path& file, double rate = 1000);

// The trajectory block of an experiment config: {type: approach-press|slide|twist|scan|circle,
// ...} or {type: recorded, file: path, ...}. Each type's keys are one parameter table
// (util/param_table.h) in trajectory.cc: parsing, the refusal of keys the type does not take,
// range checks and TrajectoryReference come from it.
struct TrajectorySpec {
  ProceduralTrajectorySpec shape;  // its type (a procedural type, or "recorded") and, for a
                                   // procedural type, the motion's keys
  bool toward = false;             // direction: toward, left to the experiment runner (it sets the
                                   // unit vector from the moving body's start to the other body's
                                   // origin); shape.direction keeps its default until then
  std::filesystem::path file;      // recorded: the CSV, found on the data search path
  // The experiment runner first moves the body along the direction until the paper's model
  // (linear, deepest level) is TOUCH_DEPTH deep.
  bool touch = false;
  double touch_depth = 1e-4;  // m
};

// Reads a trajectory block by the table of its type. Throws Error naming the file, line and
// key: a missing or unknown type, a key the type does not take (or no type takes), a value of
// the wrong type or out of range, a missing recorded file, more than kMaxTrajectorySamples
// samples.
TrajectorySpec ParseTrajectorySpec(const ConfigNode& node);

// The trajectory SPEC describes: a procedural one, or the recorded file read.
Trajectory MakeTrajectory(const TrajectorySpec& spec);

// MakeTrajectory(ParseTrajectorySpec(NODE)).
Trajectory ParseTrajectory(const ConfigNode& node);

// The trajectory tables as Markdown, one section per type (after SceneReference in
// `contactlab params` and docs/scene-reference.md).
std::string TrajectoryReference();

}  // namespace contactlab
