// Replay of a recorded manipulandum trajectory (Barbič & James 2008, sec. 6).
#include "haptics/replay_device.h"

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
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in) Fail(name, "cannot open trajectory file");
  RecordedTrajectory traj;
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    if (traj.t.empty() && std::isalpha(static_cast<unsigned char>(line[first])) && line_no == 1) continue;  // header
    // Eight comma-separated numbers.
    double v[8];
    int count = 0;
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ',')) {
      if (count == 8) FailAtLine(name, line_no, "expected 8 columns t,x,y,z,qw,qx,qy,qz, got more");
      try {
        std::size_t used = 0;
        v[count] = std::stod(item, &used);
        if (item.find_first_not_of(" \t", used) != std::string::npos) throw std::invalid_argument(item);
      } catch (const std::logic_error&) {
        FailAtLine(name, line_no, "column " + std::to_string(count + 1) + " '" + item + "' is not a number");
      }
      if (!std::isfinite(v[count])) FailAtLine(name, line_no, "column " + std::to_string(count + 1) + " is not finite");
      ++count;
    }
    if (count != 8)
      FailAtLine(name, line_no, "expected 8 columns t,x,y,z,qw,qx,qy,qz, got " + std::to_string(count));
    Eigen::Quaterniond q(v[4], v[5], v[6], v[7]);
    if (q.norm() < 1e-12) FailAtLine(name, line_no, "quaternion is zero");
    if (!traj.t.empty() && !(v[0] > traj.t.back()))
      FailAtLine(name, line_no, "time " + std::to_string(v[0]) + " is not greater than the previous row's");
    traj.t.push_back(v[0]);
    traj.X_WD.push_back(Pose{q.normalized(), Eigen::Vector3d(v[1], v[2], v[3])});
  }
  if (traj.t.empty()) Fail(name, "trajectory has no samples (expected rows t,x,y,z,qw,qx,qy,qz)");
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
