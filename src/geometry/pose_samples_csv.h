// Timestamped poses in CSV (t, x, y, z, qw, qx, qy, qz per row, seconds / metres / unit
// quaternion): the format of recorded trajectories and of session logs, read by the replay
// device and the experiment harness alike.
#pragma once

#include <filesystem>
#include <vector>

#include "geometry/pose.h"

namespace contactlab {

struct PoseSamples {
  std::vector<double> t;     // (#samples) seconds, strictly increasing
  std::vector<Pose> poses;   // (#samples) unit quaternions
};

// Reads FILE: blank lines and lines starting with '#' are skipped; the first other line may
// be a header starting with t,x,y,z,qw,qx,qy,qz (more names may follow); every row holds at
// least eight numbers (further columns, such as a session log's forces, are ignored). Throws
// Error "FILE:LINE: what" for a short row, a non-number, a non-finite value, a
// quaternion that is not unit length (NonUnitQuaternionError), a time not greater than the previous row's or a bad header; "FILE: ..." when
// the file cannot be opened or has no samples.
PoseSamples ReadPoseSamplesCsv(const std::filesystem::path& file);

}  // namespace contactlab
