// Scenes and trajectories the test suites share: the ball-on-plate scene as the YAML the
// program reads (a sphere of radius 2 cm, the pointshell, resting just above a plate of
// 10 x 10 x 2 cm, the field), the approach-press trajectory of an experiment config, and the
// ramps and presses a simulated hand follows in the haptics tests.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>
#include <string>

#include "geometry/pose.h"

namespace contactlab::testing {

// The ball-on-plate scene. The defaults are the scene most suites run; a suite that needs
// it coarser, denser or seeded changes a field. Lengths in metres.
struct BallOnPlate {
  std::string name = "ball-plate";
  double ball_z = 0.0205;         // the ball's centre: 0.5 mm above the plate's top face (z = 0)
  int sphere_subdivisions = 3;    // of the procedural sphere mesh
  int plate_subdivisions = 2;     // of the procedural box mesh
  int points = 512;               // pointshell points on the ball
  int levels = 2;                 // pointshell tree levels
  int seed = 0;                   // pointshell seed; 0 leaves it to the scene default
  int resolution = 24;            // distance-field cells, both bodies
  double k_C = 1000;              // N/m per point; 0 leaves the model block out

  // The scene as YAML, every line indented by INDENT spaces (to nest it under "scene:" in an
  // experiment config).
  std::string Yaml(int indent = 0) const {
    std::ostringstream os;
    const std::string pad(indent, ' ');
    os << pad << "name: " << name << "\n"
       << pad << "bodies:\n"
       << pad << "  - name: ball\n"
       << pad << "    mesh: \"sphere:0.02," << sphere_subdivisions << "\"\n"
       << pad << "    pose: [0, 0, " << ball_z << ", 1, 0, 0, 0]\n"
       << pad << "    role: pointshell\n"
       << pad << "    pointshell: {points: " << points << ", levels: " << levels;
    if (seed != 0) os << ", seed: " << seed;
    os << "}\n"
       << pad << "    field: {resolution: " << resolution << "}\n"
       << pad << "  - name: plate\n"
       << pad << "    mesh: \"box:0.05,0.05,0.01," << plate_subdivisions << "\"\n"
       << pad << "    pose: [0, 0, -0.01, 1, 0, 0, 0]\n"
       << pad << "    role: field\n"
       << pad << "    field: {resolution: " << resolution << "}\n";
    if (k_C > 0) os << pad << "model: {k_C: " << k_C << "}\n";
    return os.str();
  }
};

// A clamped beam pressed by a probe: the beam (10 x 1 x 1 cm half-extents 0.1, 0.01, 0.01 along
// x, clamped at its x < -0.09 end) is a deformable pointshell body (reduced StVK), the probe (a
// sphere of radius 1 cm) a rigid field body above its free end. The defaults are the haptic
// session's beam; suites that need it softer, coarser or elsewhere change a field. SI units.
struct BeamUnderProbe {
  int box_subdivisions = 4;       // of the procedural box mesh
  int points = 1024;              // pointshell points on the beam
  int levels = 3;                 // pointshell tree levels
  int beam_resolution = 64;       // the beam's distance-field cells
  int modes = 8;                  // r of the reduced model
  int cells = 24;                 // simulation-mesh voxels along the beam
  double E = 2.0e7;               // Young's modulus, Pa
  double probe_z = 0.03;          // the probe's centre, above the beam's axis at x = 0.07
  int probe_resolution = 32;      // the probe's distance-field cells
  std::string model = "{k_C: 1000, L: 10}";  // the scene's model block

  // The scene as YAML, every line indented by INDENT spaces (to nest it under "scene:").
  std::string Yaml(int indent = 0) const {
    std::ostringstream os;
    const std::string pad(indent, ' ');
    os << pad << "name: beam-probe\n"
       << pad << "bodies:\n"
       << pad << "  - name: beam\n"
       << pad << "    mesh: \"box:0.1,0.01,0.01," << box_subdivisions << "\"\n"
       << pad << "    role: pointshell\n"
       << pad << "    pointshell: {points: " << points << ", levels: " << levels << ", seed: 1}\n"
       << pad << "    field: {resolution: " << beam_resolution << "}\n"
       << pad << "    deformable: {model: stvk, modes: " << modes << ", cells: " << cells << ", E: " << E
       << ", nu: 0.3, rho: 1100,\n"
       << pad << "                 damping: {alpha: 8.0, beta: 0.0005}, anchor: {below: [x, -0.09]}}\n"
       << pad << "  - name: probe\n"
       << pad << "    mesh: \"sphere:0.01,2\"\n"
       << pad << "    pose: [0.07, 0, " << probe_z << ", 1, 0, 0, 0]\n"
       << pad << "    role: field\n"
       << pad << "    field: {resolution: " << probe_resolution << "}\n"
       << pad << "model: " << model << "\n";
    return os.str();
  }
};

// The "trajectory:" line of an experiment config pressing the moving body straight down:
// from APPROACH above its start pose to DEPTH below it and back in DURATION seconds (the
// approach-press defaults are approach 5 mm, depth 2 mm).
inline std::string PressTrajectoryYaml(double duration, double approach = 0.005, double depth = 0.002) {
  std::ostringstream os;
  os << "trajectory: {type: approach-press, direction: [0, 0, -1], approach: " << approach << ", depth: " << depth
     << ", duration: " << duration << "}";
  return os.str();
}

// 0 until T0, 1 from T1, a half cosine between: the ramps of a simulated hand's target
// (seconds).
inline double CosineRamp(double t, double t0, double t1) {
  if (t <= t0) return 0;
  if (t >= t1) return 1;
  return 0.5 - 0.5 * std::cos(M_PI * (t - t0) / (t1 - t0));
}

// A simulated hand's target pressing straight down and lifting again: at ABOVE (world frame,
// metres) until DOWN_BEGIN, TRAVEL lower from DOWN_END, held, and back at ABOVE from UP_END.
struct PressAndLift {
  Eigen::Vector3d above;
  double travel;
  double down_begin, down_end, up_begin, up_end;  // seconds
  Pose operator()(double t) const {
    const double down = CosineRamp(t, down_begin, down_end) - CosineRamp(t, up_begin, up_end);
    return Pose::FromTranslation(above - Eigen::Vector3d(0, 0, travel * down));
  }
};

}  // namespace contactlab::testing
