// The cluttered scene of the clutter benchmarks (bench_models clutter/): a tool among many
// bodies, touching the same two of them whatever their number. The tool, a ball of radius 2 cm
// (pointshell and field), rests 2 mm deep on a floor plate (20 x 20 x 2 cm) and 2 mm deep against
// a wall (2 x 20 x 8 cm); BODIES - 3 small rigid blocks (2 cm cubes) stand in a grid on the floor
// beyond the wall, 6 cm apart, none within reach of the tool. Metres.
#pragma once

#include <sstream>
#include <string>

namespace contactlab::bench {

inline std::string ClutterSceneYaml(int bodies) {
  std::ostringstream os;
  os << "name: clutter-" << bodies << "\n"
     << "tool: tool\n"
     << "bodies:\n"
     << "  - name: tool\n"
     << "    mesh: \"sphere:0.02,3\"\n"
     << "    pose: [0, 0, 0.018, 1, 0, 0, 0]\n"
     << "    pointshell: {points: 4096, levels: 4, seed: 1}\n"
     << "    field: {resolution: 48}\n"
     << "  - name: floor\n"
     << "    mesh: \"box:0.1,0.1,0.01,4\"\n"
     << "    pose: [0, 0, -0.01, 1, 0, 0, 0]\n"
     << "    field: {resolution: 64}\n"
     << "  - name: wall\n"
     << "    mesh: \"box:0.01,0.1,0.04,4\"\n"
     << "    pose: [0.028, 0, 0.04, 1, 0, 0, 0]\n"
     << "    field: {resolution: 64}\n";
  for (int i = 0; i + 3 < bodies; ++i) {
    os << "  - name: block" << i << "\n"
       << "    mesh: \"box:0.01,0.01,0.01,1\"\n"
       << "    pose: [" << 0.1 + 0.06 * (i % 16) << ", " << -0.45 + 0.06 * (i / 16) << ", 0.01, 1, 0, 0, 0]\n"
       << "    field: {resolution: 16}\n";
  }
  os << "model: {k_C: 1000, L: 10, max_point_speed: 1.0}\n";
  return os.str();
}

}  // namespace contactlab::bench
