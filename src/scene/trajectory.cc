#include "scene/trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/pose_samples_csv.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/param_table.h"

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
    if (s.type == "pass") {
      p.translation = (-s.approach + (s.approach + s.depth) * u) * dir;
    } else if (s.type == "approach-press") {
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
        Fail(where, "unknown type (approach-press, slide, twist, scan, circle, pass, recorded)");
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

namespace {

using P = ParamRows<TrajectorySpec>;

// V as the reference shows it: [x, y, z].
std::string ShowVector(const Eigen::Vector3d& v) {
  std::string s = "[";
  for (int k = 0; k < 3; ++k) s.append(k ? ", " : "").append(param_detail::Number(v[k]));
  return s.append("]");
}

// The rows the types share, DOC saying what the key does for the type.
P::Row Direction(std::string doc) {
  return P::Custom(
      "direction", "vector", "[x, y, z] not zero, or toward", std::move(doc),
      [](const ConfigNode& v, TrajectorySpec* s) {
        // "toward" (the other body) is resolved by the experiment runner.
        if (v.IsScalar() && v.AsString() == "toward") {
          s->toward = true;
          return;
        }
        s->shape.direction = Vec3(v);
        const double length = s->shape.direction.norm();
        if (length == 0) v.Fail("must be non-zero");
        // A length that overflows (components near 1e308) would normalise to zero: nothing moves.
        if (!std::isfinite(length)) v.Fail("its length overflows; give the direction with smaller numbers");
      },
      nullptr, [](const TrajectorySpec& s) { return ShowVector(s.shape.direction); });
}
P::Row Tangent(std::string doc) {
  return P::Custom(
      "tangent", "vector", "[x, y, z]", std::move(doc),
      [](const ConfigNode& v, TrajectorySpec* s) {
        s->shape.tangent = Vec3(v);
        if (!std::isfinite(s->shape.tangent.norm())) v.Fail("its length overflows; give the tangent with smaller numbers");
      },
      nullptr,
      [](const TrajectorySpec& s) { return ShowVector(s.shape.tangent); });
}
P::Row Approach() {
  return P::Number("approach", PARAM_MEMBER(shape.approach), AtLeast(0), NoUpperBound(),
                   "how far back against the direction the motion starts")
      .Unit("m");
}
P::Row Depth() {
  return P::Number("depth", PARAM_MEMBER(shape.depth), NoLowerBound(), NoUpperBound(),
                   "how far past the start pose along the direction it presses")
      .Unit("m");
}
P::Row Length(std::string doc) {
  return P::Number("length", PARAM_MEMBER(shape.length), AtLeast(0), NoUpperBound(), std::move(doc)).Unit("m");
}
std::vector<P::Row> Timing() {
  return {P::Number("duration", PARAM_MEMBER(shape.duration), Above(0), NoUpperBound(), "of the whole motion").Unit("s"),
          P::Number("rate", PARAM_MEMBER(shape.rate), Above(0), NoUpperBound(),
                    "samples per second (at most 1e8 samples: duration x rate)")
              .Unit("1/s")};
}
std::vector<P::Row> Touch() {
  return {P::Boolean("touch", PARAM_MEMBER(touch),
                     "first move the body along the direction until the paper's model (linear, deepest level) "
                     "is touch_depth deep"),
          P::Number("touch_depth", PARAM_MEMBER(touch_depth), Above(0), NoUpperBound(), "how deep touch goes")
              .Unit("m")};
}

// A procedural type's table: direction, its own rows MIDDLE, timing and touch, and the check
// that the samples stay within kMaxTrajectorySamples (before any is allocated).
ParamTable<TrajectorySpec> ProceduralTable(const std::string& type, const std::string& doc, std::vector<P::Row> middle) {
  std::vector<P::Row> rows = {Direction("the pressing direction, world frame (toward: from the moving body's start "
                                        "to the other body's origin)")};
  rows.insert(rows.end(), middle.begin(), middle.end());
  for (std::vector<P::Row> more : {Timing(), Touch()}) rows.insert(rows.end(), more.begin(), more.end());
  return ParamTable<TrajectorySpec>(
      "trajectory: {type: " + type + "}", doc, std::move(rows), [](const ConfigNode& n, TrajectorySpec* s) {
        if (s->shape.duration * s->shape.rate > kMaxTrajectorySamples) {
          const ConfigNode at = n.Has("duration") ? n.Get("duration") : n.Get("rate");
          char buf[160];
          std::snprintf(buf, sizeof buf, "duration x rate is %.3g samples (cycles), more than the limit of %.0e",
                        s->shape.duration * s->shape.rate, kMaxTrajectorySamples);
          at.Fail(buf);
        }
      });
}

// One table per trajectory type, in the order of the reference.
struct TrajectoryType {
  std::string name;
  ParamTable<TrajectorySpec> table;
};
const std::vector<TrajectoryType>& TrajectoryTypes() {
  static const std::vector<TrajectoryType> types = [] {
    std::vector<TrajectoryType> t;
    t.push_back({"approach-press",
                 ProceduralTable("approach-press",
                                 "Along the direction from -approach to +depth over the first half, and back over the "
                                 "second (smoothstep ramps).",
                                 {Approach(), Depth()})});
    t.push_back({"slide", ProceduralTable("slide",
                                          "Press to depth in the first fifth of the duration, slide length along the "
                                          "tangent and back in the middle three fifths, release in the last.",
                                          {Tangent("the slide's direction (made orthogonal to the direction)"),
                                           Approach(), Depth(), Length("how far it slides")})});
    t.push_back({"twist", ProceduralTable("twist",
                                          "Press to depth in the first fifth of the duration, rotate by angle about "
                                          "the direction and back in the middle three fifths, release in the last.",
                                          {Approach(), Depth(),
                                           P::Number("angle", PARAM_MEMBER(shape.angle), AtLeast(-1000),
                                                     AtMost(1000),
                                                     "the largest rotation about the direction, at most 1,000 rad "
                                                     "(159 turns) either way")
                                               .Unit("rad")})});
    t.push_back({"scan", ProceduralTable("scan",
                                         "Press to depth in the first fifth of the duration, sweep length along the "
                                         "tangent at constant speed (centred on the start) in the middle three fifths, "
                                         "release in the last.",
                                         {Tangent("the sweep's direction (made orthogonal to the direction)"),
                                          Approach(), Depth(), Length("how far it sweeps")})});
    t.push_back({"circle", ProceduralTable("circle",
                                           "Press to depth in the first fifth of the duration, go once round a circle "
                                           "in the plane of the tangent (from the start, which is on the circle) in "
                                           "the middle three fifths, release in the last.",
                                           {Tangent("with the direction, the plane of the circle (made orthogonal to "
                                                    "the direction)"),
                                            Approach(), Depth(),
                                            P::Number("radius", PARAM_MEMBER(shape.radius), AtLeast(0), NoUpperBound(),
                                                      "of the circle")
                                                .Unit("m")})});
    {
      // pass: no duration key; the speed sets it.
      std::vector<P::Row> rows = {
          Direction("the direction of travel, world frame (toward: from the moving body's start to the other body's "
                    "origin)"),
          Approach(), Depth(),
          P::Number("speed", PARAM_MEMBER(shape.speed), Above(0), NoUpperBound(), "constant speed along the direction")
              .Unit("m/s")
              .Example("5"),
          Timing()[1]};
      for (P::Row& r : Touch()) rows.push_back(std::move(r));
      t.push_back({"pass", ParamTable<TrajectorySpec>(
                               "trajectory: {type: pass}",
                               "Along the direction from -approach to +depth at constant speed, once, taking "
                               "(approach + depth) / speed.",
                               std::move(rows), [](const ConfigNode& n, TrajectorySpec* s) {
                                 const double length = s->shape.approach + s->shape.depth;
                                 if (!(length > 0)) n.Fail("approach + depth must be positive for a pass");
                                 s->shape.duration = length / s->shape.speed;
                                 if (s->shape.duration * s->shape.rate > kMaxTrajectorySamples) {
                                   n.Get("speed").Fail("(approach + depth) / speed x rate is more than the limit of "
                                                       "1e8 samples");
                                 }
                               })});
    }
    std::vector<P::Row> recorded = {
        P::Custom("file", "text", "a CSV file on the data search path",
                  "t,x,y,z,qw,qx,qy,qz rows, e.g. a session log (required)",
                  [](const ConfigNode& v, TrajectorySpec* s) {
                    s->file = RequireDataFile(v.AsString(), FolderOf(v.file()));
                  },
                  nullptr, [](const TrajectorySpec&) { return std::string(); }),
        Direction("the direction of touch (toward: from the moving body's start to the other body's origin)")};
    for (P::Row& r : Touch()) recorded.push_back(std::move(r));
    t.push_back({"recorded",
                 ParamTable<TrajectorySpec>("trajectory: {type: recorded}",
                                            "The poses of a recorded file at its own times, relative to its first "
                                            "row (interpolated between rows, slerp for the rotation).",
                                            std::move(recorded),
                                            [](const ConfigNode& n, TrajectorySpec*) { (void)n.Get("file"); })});
    return t;
  }();
  return types;
}

// The types' names, as a list for messages and the reference.
std::string TypeList() {
  std::string list;
  for (const TrajectoryType& t : TrajectoryTypes()) list += (list.empty() ? "" : ", ") + t.name;
  return list;
}

// The block's one common key: its type, which chooses the table of the rest.
const ParamTable<TrajectorySpec>& TypeTable() {
  static const ParamTable<TrajectorySpec> table(
      "trajectory",
      "The motion of the moving body in an experiment config (tables in `src/scene/trajectory.cc`), relative to "
      "its start pose: translation in the world frame, rotation about the body's origin. Its type chooses the other "
      "keys (below); a sweep names them by their path (`trajectory.depth`).",
      {P::Custom("type", "choice", TypeList(), "the kind of motion (required)",
                 [](const ConfigNode& v, TrajectorySpec* s) {
                   const std::string name = v.AsString();
                   for (const TrajectoryType& t : TrajectoryTypes()) {
                     if (t.name == name) {
                       s->shape.type = name;
                       return;
                     }
                   }
                   v.Fail("'" + v.Quoted() + "' is not one of: " + TypeList());
                 },
                 nullptr, [](const TrajectorySpec&) { return std::string(); })});
  return table;
}

}  // namespace

TrajectorySpec ParseTrajectorySpec(const ConfigNode& n) {
  n.ExpectMap();
  // The type, which chooses the table.
  TrajectorySpec spec;
  TypeTable().rows().front().read(n.Get("type"), &spec);
  const TrajectoryType& type = *std::find_if(TrajectoryTypes().begin(), TrajectoryTypes().end(),
                                             [&](const TrajectoryType& t) { return t.name == spec.shape.type; });
  // A key that only other types take is named as such (the table's Parse refuses any other
  // unknown key).
  for (const std::string& key : n.Keys()) {
    if (key == "type" || type.table.Find(key)) continue;
    std::string others;
    for (const TrajectoryType& t : TrajectoryTypes()) {
      if (t.table.Find(key)) others += (others.empty() ? "" : ", ") + t.name;
    }
    if (others.empty()) continue;
    std::string keys = "type";
    for (const std::string& k : type.table.Keys()) keys += ", " + k;
    n.Get(key).Fail("not a key of type " + type.name + ", only of " + others + " (" + type.name + " takes: " + keys + ")");
  }
  // The type's own keys, by its table.
  return type.table.Parse(n, spec, {"type"});
}

Trajectory MakeTrajectory(const TrajectorySpec& spec) {
  if (spec.shape.type == "recorded") return LoadTrajectoryCsv(spec.file);
  return MakeProceduralTrajectory(spec.shape);
}

Trajectory ParseTrajectory(const ConfigNode& n) { return MakeTrajectory(ParseTrajectorySpec(n)); }

std::string TrajectoryReference() {
  std::string s = TypeTable().Reference("trajectory");
  for (const TrajectoryType& t : TrajectoryTypes()) {
    TrajectorySpec defaults;
    defaults.shape.type = t.name;
    s += t.table.Reference(t.table.name(), defaults);
  }
  return s;
}

}  // namespace contactlab
