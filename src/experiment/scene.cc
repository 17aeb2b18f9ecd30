#include "experiment/scene.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "sdf/sparse_field.h"
#include "util/error.h"

namespace contactlab {
namespace {

FieldSpec ParseField(const ConfigNode& n) {
  n.ExpectKeys({"resolution", "mode", "padding", "offset", "storage", "band"});
  FieldSpec f;
  f.resolution = int(n.IntInRange("resolution", f.resolution, 8, kMaxFieldResolution));
  f.mode = n.OneOf("mode", f.mode, {"auto", "closed", "soup"});
  f.storage = n.OneOf("storage", f.storage, {"dense", "sparse"});
  f.band = int(n.IntInRange("band", f.band, 1, SparseFieldStorage::kMaxBand));
  if (f.storage == "sparse") {
    if (f.mode == "soup") n.Get("mode").Fail("a sparse field needs the closed pipeline (mode auto or closed)");
    if (!SparseFieldStorage::ResolutionFits(f.resolution)) {
      n.Get("resolution").Fail("a sparse field needs a resolution that is a multiple of 8 and at least " +
                               std::to_string(SparseFieldStorage::kMinResolution));
    }
  } else if (n.Has("band")) {
    n.Get("band").Fail("band applies to storage: sparse only");
  }
  f.padding = n.NonNegative("padding", f.padding);
  if (n.Has("offset")) f.offset = n.Positive("offset", 0);
  return f;
}

PointshellSpec ParsePointshell(const ConfigNode& n) {
  n.ExpectKeys({"points", "levels", "method", "seed", "offset"});
  PointshellSpec s;
  s.points = int(n.IntInRange("points", s.points, 1, kMaxPointshellPoints));
  s.levels = int(n.IntInRange("levels", s.levels, 1, kMaxPointshellLevels));
  s.method = n.OneOf("method", s.method, {"repulsion", "voxel", "vertices", "random"});
  s.seed = std::uint64_t(n.Int("seed", (long long)s.seed));
  if (n.Has("offset")) s.offset = n.NonNegative("offset", 0);
  return s;
}

// anchor: none | {below: [axis, value]} | {box: [x0, y0, z0, x1, y1, z1]} (fixed inside) |
// {outside: [x0, y0, z0, x1, y1, z1]} (fixed outside, e.g. both ends of a bridge).
Anchoring ParseAnchor(const ConfigNode& n) {
  if (n.IsScalar()) {
    if (n.AsString() != "none") {
      n.Fail("expected none, {below: [axis, value]}, {box: [x0, y0, z0, x1, y1, z1]} or {outside: [...]}");
    }
    return Anchoring::Free();
  }
  n.ExpectKeys({"below", "box", "outside"});
  if (int(n.Has("below")) + int(n.Has("box")) + int(n.Has("outside")) != 1) {
    n.Fail("give exactly one of below, box and outside");
  }
  if (auto b = n.Find("below")) {
    const std::vector<ConfigNode> e = b->Elements();
    if (e.size() != 2) b->Fail("needs [axis, value], e.g. [y, -0.02]");
    const std::string axis = e[0].AsString();
    if (axis != "x" && axis != "y" && axis != "z") e[0].Fail("the axis must be x, y or z, got '" + axis + "'");
    return Anchoring::BelowPlane(Eigen::Vector3d::Unit(axis[0] - 'x'), e[1].AsDouble());
  }
  const bool outside = n.Has("outside");
  const ConfigNode box = n.Get(outside ? "outside" : "box");
  const std::vector<double> v = box.AsDoubles();
  if (v.size() != 6) box.Fail("needs 6 numbers x0, y0, z0, x1, y1, z1");
  Aabb a;
  a.min = Eigen::Vector3d(v[0], v[1], v[2]);
  a.max = Eigen::Vector3d(v[3], v[4], v[5]);
  if (!(a.min.array() < a.max.array()).all()) box.Fail("the first corner must be below the second on every axis");
  return outside ? Anchoring::OutsideBox(a) : Anchoring::InBox(a);
}

// One domain of a deformed field: {box: [x0, y0, z0, x1, y1, z1]} or {halfspace: [nx, ny, nz, c]}
// (the side n . X <= c), body frame after scale and centring.
DomainRegion ParseDomain(const ConfigNode& n) {
  n.ExpectKeys({"box", "halfspace"});
  if (int(n.Has("box")) + int(n.Has("halfspace")) != 1) n.Fail("give exactly one of box and halfspace");
  if (auto b = n.Find("box")) {
    const std::vector<double> v = b->AsDoubles();
    if (v.size() != 6) b->Fail("needs 6 numbers x0, y0, z0, x1, y1, z1");
    Aabb a;
    a.min = Eigen::Vector3d(v[0], v[1], v[2]);
    a.max = Eigen::Vector3d(v[3], v[4], v[5]);
    if (!(a.min.array() < a.max.array()).all()) b->Fail("the first corner must be below the second on every axis");
    return DomainRegion::Box(a);
  }
  const ConfigNode h = n.Get("halfspace");
  const std::vector<double> v = h.AsDoubles();
  if (v.size() != 4) h.Fail("needs 4 numbers nx, ny, nz, c (the side n . X <= c)");
  const Eigen::Vector3d normal(v[0], v[1], v[2]);
  if (!(normal.norm() > 0) || !std::isfinite(v[3])) h.Fail("needs a non-zero normal and a finite offset");
  return DomainRegion::Halfspace(normal, v[3]);
}

// The deformed distance field of a deformable field body (paper sec. 4.2).
DeformedFieldOptions ParseDeformedField(const ConfigNode& n) {
  n.ExpectKeys({"proxies", "neighbours", "domains", "overlap", "seed", "force_at"});
  DeformedFieldOptions o;
  o.proxies = int(n.IntInRange("proxies", o.proxies, 2, 4096));
  o.neighbours = int(n.IntInRange("neighbours", o.neighbours, 2, kMaxProxyNeighbours));
  if (o.proxies < o.neighbours) n.Get("proxies").Fail("must be at least neighbours (" + std::to_string(o.neighbours) + ")");
  if (auto d = n.Find("domains")) {
    if (d->IsSequence()) {
      for (const ConfigNode& e : d->Elements()) o.regions.push_back(ParseDomain(e));
      if (o.regions.empty() || o.regions.size() > 64) d->Fail("needs 1 to 64 domains");
    } else {
      o.domains = int(n.IntInRange("domains", 1, 1, 64));
      if (o.domains > o.proxies / 2 && o.domains > 1) {
        d->Fail("at most proxies / 2 = " + std::to_string(o.proxies / 2) + " automatic domains");
      }
    }
  }
  o.overlap = n.NonNegative("overlap", -1.0);
  o.seed = std::uint64_t(n.IntInRange("seed", 1, 0, std::numeric_limits<std::int32_t>::max()));
  o.force_at = n.OneOf("force_at", "nearest", {"nearest", "weighted"}) == "nearest"
                   ? DeformedFieldOptions::ForceAt::kNearestProxy
                   : DeformedFieldOptions::ForceAt::kWeightedProxies;
  return o;
}

DeformableSpec ParseDeformable(const ConfigNode& n) {
  n.ExpectKeys({"model", "modes", "cells", "E", "nu", "rho", "damping", "anchor", "coupling", "field"});
  DeformableSpec d;
  d.kind = n.OneOf("model", "stvk", {"stvk", "linear"}) == "linear" ? ReducedModelKind::kLinear
                                                                    : ReducedModelKind::kStVK;
  if (auto c = n.Find("modes")) {
    const long long r = c->AsInt();
    if (r < 1 || r > kMaxReducedModes) c->Fail("must be between 1 and " + std::to_string(kMaxReducedModes));
    d.modes = int(r);
  }
  if (auto c = n.Find("cells")) {
    const long long cells = c->AsInt();
    if (cells < 1 || cells > 256) c->Fail("must be between 1 and 256");
    d.cells = int(cells);
  }
  d.material.youngs_modulus = n.Positive("E", d.material.youngs_modulus);
  if (auto c = n.Find("nu")) {
    d.material.poisson_ratio = c->AsDouble();
    if (!(d.material.poisson_ratio > -1 && d.material.poisson_ratio < 0.5)) c->Fail("must be in (-1, 0.5)");
  }
  d.material.density = n.Positive("rho", d.material.density);
  if (auto c = n.Find("damping")) {
    c->ExpectKeys({"alpha", "beta"});
    d.mass_damping = c->NonNegative("alpha", d.mass_damping);
    d.stiffness_damping = c->NonNegative("beta", d.stiffness_damping);
  }
  if (auto c = n.Find("anchor")) d.anchor = ParseAnchor(*c);
  d.implicit_contact = n.OneOf("coupling", "implicit", {"implicit", "explicit"}) == "implicit";
  if (auto f = n.Find("field")) d.field = ParseDeformedField(*f);
  return d;
}

BodySpec ParseBody(const ConfigNode& n) {
  n.ExpectKeys({"name", "mesh", "scale", "center", "pose", "role", "field", "pointshell", "deformable"});
  BodySpec b;
  b.mesh = n.Get("mesh").AsString();
  b.mesh_where = n.Get("mesh").Location();
  b.name = n.String("name", b.mesh);
  b.scale = n.Positive("scale", 1.0);
  b.center = n.Bool("center", false);
  if (auto p = n.Find("pose")) b.pose = ParsePoseNode(*p);
  b.role = n.Get("role").AsString();
  if (b.role != "pointshell" && b.role != "field") n.Get("role").Fail("must be 'pointshell' or 'field', got '" + b.role + "'");
  if (auto f = n.Find("field")) b.field = ParseField(*f);
  if (auto s = n.Find("pointshell")) b.pointshell = ParsePointshell(*s);
  if (auto d = n.Find("deformable")) b.deformable = ParseDeformable(*d);
  if (b.deformable && b.field.storage == "sparse") {
    n.Get("field").Get("storage").Fail("a deformable body needs a dense field (its reduced model and deformed field read every sample)");
  }
  return b;
}

// The model section: the paper's model's parameters (checked where they are defined) and the
// node budget.
void ParseModel(const ConfigNode& n, Scene* scene) {
  n.ExpectKeys({"k_C", "L", "level", "coherence", "max_point_speed", "cycle_seconds", "lipschitz", "cold_fraction",
                "gradient", "node_budget", "warm_threshold"});
  scene->model = ParsePointshellContactParams(n);
  if (n.Has("node_budget") && n.Has("warm_threshold")) n.Fail("give node_budget or warm_threshold, not both");
  for (const char* key : {"node_budget", "warm_threshold"}) {
    if (auto c = n.Find(key)) {
      scene->node_budget = c->AsInt();
      if (scene->node_budget < 0) c->Fail("must not be negative");
    }
  }
}

}  // namespace

Pose ParsePoseNode(const ConfigNode& n) {
  if (n.IsSequence()) {
    const std::vector<double> v = n.AsDoubles();
    if (v.size() != 7) n.Fail("a pose list needs 7 numbers x, y, z, qw, qx, qy, qz");
    Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (q.norm() < 1e-12) n.Fail("the quaternion is zero");
    return {q.normalized(), Eigen::Vector3d(v[0], v[1], v[2])};
  }
  n.ExpectKeys({"position", "rotation", "rotation_vector"});
  Pose pose;
  if (auto p = n.Find("position")) {
    const std::vector<double> v = p->AsDoubles();
    if (v.size() != 3) p->Fail("needs 3 numbers");
    pose.translation = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  if (n.Has("rotation") && n.Has("rotation_vector")) n.Fail("give rotation or rotation_vector, not both");
  if (auto r = n.Find("rotation")) {
    const std::vector<double> v = r->AsDoubles();
    if (v.size() != 4) r->Fail("needs a quaternion qw, qx, qy, qz");
    Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (q.norm() < 1e-12) r->Fail("the quaternion is zero");
    pose.rotation = q.normalized();
  }
  if (auto r = n.Find("rotation_vector")) {
    const std::vector<double> v = r->AsDoubles();
    if (v.size() != 3) r->Fail("needs 3 numbers (axis times angle, radians)");
    pose.rotation = RotationFromVector(Eigen::Vector3d(v[0], v[1], v[2]));
  }
  return pose;
}

Scene ParseScene(const ConfigNode& n) {
  n.ExpectKeys({"name", "bodies", "model", "models"});
  Scene scene;
  scene.file = n.file();
  scene.name = n.String("name", std::filesystem::path(n.file()).stem().string());
  const std::vector<ConfigNode> bodies = n.Get("bodies").Elements();
  if (bodies.size() != 2) n.Get("bodies").Fail("a scene needs exactly two bodies, got " + std::to_string(bodies.size()));
  BodySpec a = ParseBody(bodies[0]);
  BodySpec b = ParseBody(bodies[1]);
  if (a.role == b.role) bodies[1].Get("role").Fail("the two bodies need different roles (one pointshell, one field)");
  if (a.role == "field") std::swap(a, b);
  scene.pointshell_body = a;
  scene.field_body = b;
  if (auto m = n.Find("model")) ParseModel(*m, &scene);
  if (auto ms = n.Find("models")) {
    for (const ConfigNode& e : ms->Elements()) scene.models.push_back(e.AsString());
    if (scene.models.empty()) ms->Fail("lists no model");
  } else {
    scene.models = {"pointshell"};
  }
  return scene;
}

Scene LoadScene(const std::filesystem::path& file) { return ParseScene(ConfigNode::LoadFile(file)); }

Scene Scene::Swapped() const {
  Scene s = *this;
  std::swap(s.pointshell_body, s.field_body);
  s.pointshell_body.role = "pointshell";
  s.field_body.role = "field";
  s.name = name + " (roles swapped)";
  return s;
}

}  // namespace contactlab
