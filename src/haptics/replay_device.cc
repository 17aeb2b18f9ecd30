// Replay of a recorded manipulandum trajectory (Barbič & James 2008, sec. 6).
#include "haptics/replay_device.h"

#include "geometry/pose_samples_csv.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "util/error.h"

namespace contactlab {

Pose RecordedTrajectory::Sample(double time, std::size_t* cursor) const {
  const std::size_t n = t.size();
  if (n == 0) return Pose{};
  const double tq = t.front() + time;
  if (tq <= t.front()) return X_WD.front();
  if (tq >= t.back()) return X_WD.back();
  std::size_t i = (cursor != nullptr && *cursor < n - 1 && t[*cursor] <= tq) ? *cursor : 0;
  while (i + 1 < n - 1 && t[i + 1] <= tq) ++i;
  if (cursor != nullptr) *cursor = i;
  const double s = (tq - t[i]) / (t[i + 1] - t[i]);
  return Interpolate(X_WD[i], X_WD[i + 1], s);
}

RecordedTrajectory ReadTrajectoryCsv(const std::filesystem::path& file) {
  PoseSamples samples = ReadPoseSamplesCsv(file);
  RecordedTrajectory traj;
  traj.t = std::move(samples.t);
  traj.X_WD = std::move(samples.poses);
  return traj;
}

ReplayDevice::ReplayDevice(RecordedTrajectory trajectory, const DeviceCapabilities& capabilities)
    : trajectory_(std::move(trajectory)), capabilities_(capabilities) {
  if (trajectory_.t.empty() || trajectory_.t.size() != trajectory_.X_WD.size())
    Fail("replay device", "trajectory is empty or its time and pose arrays differ in length");
}

bool ReplayDevice::Read(std::int64_t now_ns, DeviceState* out) {
  if (!started_) {
    started_ = true;
    t0_ns_ = now_ns;
  }
  const double t = 1e-9 * double(now_ns - t0_ns_);
  finished_ = t >= trajectory_.duration();
  out->X_WD = trajectory_.Sample(t, &cursor_);
  out->timestamp_ns = now_ns;
  out->buttons = 0;
  out->sequence = ++sequence_;
  return true;
}

}  // namespace contactlab
