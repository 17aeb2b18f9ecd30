#include "experiment/trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/pose_samples_csv.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"

namespace contactlab {
namespace {

double Smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

Eigen::Vector3d Vec3(const ConfigNode& n) {
  const std::vector<double> v = n.AsDoubles();
  if (v.size() != 3) n.Fail("needs 3 numbers");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

}  // namespace

Trajectory::Trajectory(std::vector<double> times, std::vector<Pose> poses, std::string description)
    : times_(std::move(times)), poses_(std::move(poses)), description_(std::move(description)) {
  if (times_.size() < 2 || times_.size() != poses_.size()) Fail(description_, "a trajectory needs at least two samples");
  for (std::size_t i = 1; i < times_.size(); ++i) {
    if (!(times_[i] > times_[i - 1])) Fail(description_, "sample times must increase");
  }
}

Pose Trajectory::At(double t) const {
  if (t <= times_.front()) return poses_.front();
  if (t >= times_.back()) return poses_.back();
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  const std::size_t i = std::size_t(it - times_.begin()) - 1;
  const double s = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return Interpolate(poses_[i], poses_[i + 1], s);
}

double Trajectory::MaxPointSpeed(double radius) const {
  double best = 0;
  for (std::size_t i = 1; i < times_.size(); ++i) {
    const double dt = times_[i] - times_[i - 1];
    const double v = (poses_[i].translation - poses_[i - 1].translation).norm() / dt;
    const double w = poses_[i].rotation.angularDistance(poses_[i - 1].rotation) / dt;
    best = std::max(best, v + w * radius);
  }
  return best;
}

Trajectory MakeProceduralTrajectory(const ProceduralTrajectorySpec& s) {
  const std::string where = "trajectory '" + s.type + "'";
  if (!(s.duration > 0) || !(s.rate > 0)) Fail(where, "duration and rate must be positive");
  if (!(s.duration * s.rate <= kMaxTrajectorySamples)) {
    Fail(where, "duration x rate is more than the limit of 1e8 samples");
  }
  if (s.direction.norm() == 0) Fail(where, "direction must be non-zero");
  const Eigen::Vector3d dir = s.direction.normalized();
  Eigen::Vector3d tangent = s.tangent - s.tangent.dot(dir) * dir;
  if (tangent.norm() < 1e-9) tangent = dir.unitOrthogonal();
  tangent.normalize();
  const Eigen::Vector3d binormal = dir.cross(tangent);
  const int n = std::max(2, int(std::round(s.duration * s.rate)) + 1);
  std::vector<double> times(n);
  std::vector<Pose> poses(n);
  for (int i = 0; i < n; ++i) {
    const double t = s.duration * i / (n - 1);
    const double u = t / s.duration;  // 0..1
    Pose p;
    if (s.type == "approach-press") {
      // Down from -approach to +depth over the first half, back up over the second.
      const double travel = -s.approach + (s.approach + s.depth) * Smoothstep(u < 0.5 ? 2 * u : 2 - 2 * u);
      p.translation = travel * dir;
    } else {
      // Press in the first fifth, act in the middle, release in the last fifth.
      const double press = Smoothstep(u / 0.2) * (u <= 0.8 ? 1.0 : Smoothstep((1 - u) / 0.2));
      p.translation = (-s.approach + (s.approach + s.depth) * press) * dir;
      const double a = std::clamp((u - 0.2) / 0.6, 0.0, 1.0);  // 0..1 during the action
      if (s.type == "slide") {
        p.translation += s.length * std::sin(M_PI * a) * tangent;
      } else if (s.type == "twist") {
        p.rotation = RotationFromVector(s.angle * std::sin(M_PI * a) * dir);
      } else if (s.type == "scan") {
        p.translation += s.length * (a - 0.5) * tangent;
      } else if (s.type == "circle") {
        const double phi = 2 * M_PI * a;
        p.translation += s.radius * ((std::cos(phi) - 1) * tangent + std::sin(phi) * binormal);
      } else {
        Fail(where, "unknown type (approach-press, slide, twist, scan, circle, recorded)");
      }
    }
    times[i] = t;
    poses[i] = p;
  }
  return Trajectory(std::move(times), std::move(poses), where);
}

Trajectory LoadTrajectoryCsv(const std::filesystem::path& file) {
  PoseSamples samples = ReadPoseSamplesCsv(file);
  if (samples.t.size() < 2) Fail(file.string(), "a recorded trajectory needs at least two rows");
  // Relative to the first sample, like the procedural ones: translation in the world frame,
  // rotation as a world-frame rotation applied before the start orientation.
  const Eigen::Vector3d p0 = samples.poses.front().translation;
  const Eigen::Quaterniond q0 = samples.poses.front().rotation;
  for (Pose& pose : samples.poses) pose = Pose{(pose.rotation * q0.conjugate()).normalized(), pose.translation - p0};
  return Trajectory(std::move(samples.t), std::move(samples.poses), file.string());
}

void SaveTrajectoryCsv(const Trajectory& trajectory, const std::filesystem::path& file, double rate) {
  WriteFileAtomically(file, [&](std::ostream& out) {
    out << "t,x,y,z,qw,qx,qy,qz\n";
    const int n = std::max(2, int(std::round(trajectory.duration() * rate)) + 1);
    char buf[256];
    for (int i = 0; i < n; ++i) {
      const double t = trajectory.start_time() + trajectory.duration() * i / (n - 1);
      const Pose p = trajectory.At(t);
      std::snprintf(buf, sizeof buf, "%.6f,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, p.translation.x(),
                    p.translation.y(), p.translation.z(), p.rotation.w(), p.rotation.x(), p.rotation.y(),
                    p.rotation.z());
      out << buf;
    }
  });
}

Trajectory ParseTrajectory(const ConfigNode& n) {
  const std::string type = n.Get("type").AsString();
  if (type == "recorded") {
    n.ExpectKeys({"type", "file", "touch", "touch_depth", "direction"});
    return LoadTrajectoryCsv(RequireDataFile(n.Get("file").AsString(), FolderOf(n.file())));
  }
  n.ExpectKeys({"type", "direction", "tangent", "approach", "depth", "length", "radius", "angle", "duration", "rate",
                "touch", "touch_depth"});
  ProceduralTrajectorySpec s;
  s.type = n.OneOf("type", s.type, {"approach-press", "slide", "twist", "scan", "circle"});
  // "toward" (the other body) is resolved by the experiment runner; checked here as a placeholder.
  if (auto d = n.Find("direction"); d && !(d->IsScalar() && d->AsString() == "toward")) s.direction = Vec3(*d);
  if (auto d = n.Find("tangent")) s.tangent = Vec3(*d);
  if (s.direction.norm() == 0) n.Get("direction").Fail("must be non-zero");
  s.approach = n.NonNegative("approach", s.approach);
  s.depth = n.Double("depth", s.depth);
  s.length = n.NonNegative("length", s.length);
  s.radius = n.NonNegative("radius", s.radius);
  s.angle = n.Double("angle", s.angle);
  s.duration = n.Positive("duration", s.duration);
  s.rate = n.Positive("rate", s.rate);
  // Bounded before the samples are allocated (one per cycle).
  if (s.duration * s.rate > kMaxTrajectorySamples) {
    const ConfigNode at = n.Has("duration") ? n.Get("duration") : n.Get("rate");
    char buf[160];
    std::snprintf(buf, sizeof buf, "duration x rate is %.3g samples (cycles), more than the limit of %.0e",
                  s.duration * s.rate, kMaxTrajectorySamples);
    at.Fail(buf);
  }
  return MakeProceduralTrajectory(s);
}

}  // namespace contactlab
