#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "contact/model_registry.h"
#include "contact/register_contact_models.h"
#include "sdf/build_distance_field.h"
#include "sdf/sparse_field.h"
#include "util/error.h"
#include "util/hasher.h"

namespace contactlab {
namespace {

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

void HashAnchor(const Anchoring& a, Hasher* h) {
  h->Value(std::int32_t(a.kind));
  h->Value(a.normal.x()), h->Value(a.normal.y()), h->Value(a.normal.z());
  h->Value(a.offset);
  if (a.kind == Anchoring::Kind::kInBox || a.kind == Anchoring::Kind::kOutsideBox) {
    for (int i = 0; i < 3; ++i) h->Value(a.box.min[i]), h->Value(a.box.max[i]);
  }
}

void HashDomains(const DeformedFieldOptions& o, Hasher* h) {
  h->Value(o.domains);
  for (const DomainRegion& r : o.regions) {
    for (const Eigen::Vector4d& p : r.planes) h->Bytes(p.data(), sizeof(double) * 4);
  }
}

// The damping: {alpha, beta} of the deformable block itself.
const ParamTable<DeformableSpec>& DampingParams() {
  using P = ParamRows<DeformableSpec>;
  static const ParamTable<DeformableSpec> table(
      "bodies[].deformable.damping", "Rayleigh damping of the reduced dynamics: D = alpha M + beta K.",
      {
          P::Number("alpha", PARAM_MEMBER(mass_damping), AtLeast(0), NoUpperBound(), "mass-proportional damping")
              .Unit("1/s").Example("2"),
          P::Number("beta", PARAM_MEMBER(stiffness_damping), AtLeast(0), NoUpperBound(),
                    "stiffness-proportional damping")
              .Unit("s").Example("0.001"),
      });
  return table;
}

// A value built from the registered contact models (their keys and blocks), built again when a
// model registers after it was built (a test's model, a Python model). Earlier versions are
// kept, so a reference handed out stays valid.
template <class T, class Build>
const T& BuiltFromRegistry(Build build) {
  static std::mutex mutex;
  static std::vector<std::unique_ptr<const T>> versions;
  static std::uint64_t built_at = 0;
  RegisterContactModels();
  const std::lock_guard<std::mutex> lock(mutex);
  if (versions.empty() || built_at != ContactModelRegistryVersion()) {
    built_at = ContactModelRegistryVersion();
    versions.push_back(std::make_unique<const T>(build()));
  }
  return *versions.back();
}

// The registered models' blocks of one kind (MEMBER: a pair block, or each body block), each
// table once however many entries carry it, with the models that carry it.
struct RegisteredBlock {
  const ModelParamBlock* block;
  std::string models;
};
std::vector<RegisteredBlock> RegisteredBlocks(bool body) {
  std::vector<RegisteredBlock> blocks;
  for (const ContactModelEntry* e : ContactModelEntries()) {
    std::vector<const ModelParamBlock*> own;
    if (!body && e->pair_params) own.push_back(&*e->pair_params);
    if (body) {
      for (const ModelParamBlock& b : e->body_blocks) own.push_back(&b);
    }
    for (const ModelParamBlock* b : own) {
      const auto same = std::find_if(blocks.begin(), blocks.end(), [b](const RegisteredBlock& r) {
        return r.block->table->name() == b->table->name() && r.block->key == b->key;
      });
      if (same == blocks.end()) {
        blocks.push_back({b, e->name});
      } else {
        same->models += ", " + e->name;
      }
    }
  }
  return blocks;
}

// Fails when KEY is already one of ROWS, naming the model that brings it again.
template <class Spec>
void ExpectNewKey(const std::vector<ParamRow<Spec>>& rows, const std::string& key, const std::string& section,
                  const std::string& models) {
  for (const auto& r : rows) {
    if (r.key == key) {
      throw std::logic_error("contact model(s) " + models + ": key '" + key + "' of " + section + " is taken");
    }
  }
}

const ParamTable<Scene>& ModelSectionParams() {
  return BuiltFromRegistry<ParamTable<Scene>>([] {
    using P = ParamRows<Scene>;
    std::vector<ParamRow<Scene>> rows = P::Lifted(ContactParamTable(), PARAM_MEMBER(model));
    rows.push_back(P::Integer("node_budget", PARAM_MEMBER(node_budget), 0, P::kNoLimit,
                              "warm threshold V_W: nodes per cycle before graceful degradation (0: unlimited)")
                       .Sweepable()
                       .Example("500"));
    rows.push_back(P::Integer("warm_threshold", PARAM_MEMBER(node_budget), 0, P::kNoLimit, "node_budget's other name")
                       .Example("500"));
    // Each registered model's own keys, read into the scene's model_params.
    for (const RegisteredBlock& r : RegisteredBlocks(false)) {
      for (ParamRow<Scene>& row : P::Lifted(*r.block->table, PARAM_MEMBER(model_params))) {
        ExpectNewKey(rows, row.key, "the model section", r.models);
        rows.push_back(std::move(row));
      }
    }
    return ParamTable<Scene>(
        "model",
        ContactParamTable().doc() + " node_budget is handed to each query; the other keys are the registered models' "
                                    "own (the model named first in the meaning).",
        std::move(rows), [](const ConfigNode& n, Scene*) {
          if (n.Has("node_budget") && n.Has("warm_threshold")) n.Fail("give node_budget or warm_threshold, not both");
        });
  });
}

}  // namespace

const ParamTable<FieldSpec>& FieldParams() {
  using P = ParamRows<FieldSpec>;
  constexpr unsigned kAll = kShapesField | kShapesPointshell | kShapesReducedModel;  // all are built from the field
  static const ParamTable<FieldSpec> table(
      "bodies[].field", "The body's signed distance field (a regular grid over its padded bounding box).",
      {
          P::Integer("resolution", PARAM_MEMBER(resolution), 8, kMaxFieldResolution, "cells along the longest side")
              .Shapes(kAll).Sweepable().Example("24"),
          P::Choice("mode", PARAM_MEMBER(mode), {"auto", "closed", "soup"},
                    "closed (inside/outside by winding), soup (an iso-offset of the unsigned distance), or auto")
              .Shapes(kAll).Example("soup"),
          P::Number("padding", PARAM_MEMBER(padding), AtLeast(0), AtMost(kMaxFieldPadding),
                    "margin around the bounding box, a fraction of its largest extent (at most 4, so that the "
                    "body spans at least a ninth of the cells)")
              .Shapes(kAll).Example("0.2"),
          P::Number("offset", PARAM_MEMBER(offset), Above(0), NoUpperBound(), "soup iso-offset")
              .Unit("m").Shapes(kAll).Default("the builder's").Example("0.002"),
          P::Choice("storage", PARAM_MEMBER(storage), {"dense", "sparse"},
                    "dense, or sparse: a fine band over a 1/8-resolution field")
              .Shapes(kAll).Example("sparse"),
          P::Integer("band", PARAM_MEMBER(band), 1, SparseFieldStorage::kMaxBand,
                     "sparse: voxels of fine samples on each side of the surface")
              .Shapes(kAll).Example("2"),
      },
      [](const ConfigNode& n, FieldSpec* f) {
        if (f->storage == "sparse") {
          if (f->mode == "soup") n.Get("mode").Fail("a sparse field needs the closed pipeline (mode auto or closed)");
          if (!SparseFieldStorage::ResolutionFits(f->resolution)) {
            (n.Has("resolution") ? n.Get("resolution") : n)
                .Fail("a sparse field needs a resolution that is a multiple of 8 and at least " +
                      std::to_string(SparseFieldStorage::kMinResolution));
          }
        } else if (n.Has("band")) {
          n.Get("band").Fail("band applies to storage: sparse only");
        }
      });
  return table;
}

const ParamTable<PointshellSpec>& PointshellParams() {
  using P = ParamRows<PointshellSpec>;
  static const ParamTable<PointshellSpec> table(
      "bodies[].pointshell", "The body's pointshell: points on its offset surface in a nested tree (sec. 3).",
      {
          P::Integer("points", PARAM_MEMBER(points), 1, kMaxPointshellPoints, "points on the deepest level")
              .Shapes(kShapesPointshell).Sweepable().Example("100"),
          P::Integer("levels", PARAM_MEMBER(levels), 1, kMaxPointshellLevels, "tree levels")
              .Shapes(kShapesPointshell).Sweepable().Example("3"),
          P::Choice("method", PARAM_MEMBER(method), {"repulsion", "voxel", "vertices", "random"},
                    "how the points are placed")
              .Shapes(kShapesPointshell).Sweepable().Example("random"),
          P::Integer("seed", PARAM_MEMBER(seed), 0, P::kNoLimit, "random seed of the placement")
              .Shapes(kShapesPointshell).Sweepable().Example("7"),
          P::Number("offset", PARAM_MEMBER(offset), AtLeast(0), NoUpperBound(), "level-set offset delta")
              .Unit("m").Shapes(kShapesPointshell).Sweepable().Default("the builder's").Example("0.0005"),
      });
  return table;
}

const ParamTable<DeformedFieldOptions>& DeformedFieldParams() {
  using P = ParamRows<DeformedFieldOptions>;
  static const ParamTable<DeformedFieldOptions> table(
      "bodies[].deformable.field",
      "A deformable field body's deformed distance field (sec. 4.2), built in memory from its reduced model.",
      {
          P::Integer("proxies", PARAM_MEMBER(proxies), 2, 4096, "proxyshell points fitted to the whole body")
              .Sweepable().Example("12"),
          P::Integer("neighbours", PARAM_MEMBER(neighbours), 2, kMaxProxyNeighbours, "k of the k-nearest proxies")
              .Sweepable().Example("3"),
          P::Custom(
               "domains", "integer or list", "1 to 64, or [{box: [...]} | {halfspace: [nx, ny, nz, c]}, ...]",
               "automatic domains (k-means of the proxies, at most proxies / 2), or explicit convex regions",
               [](const ConfigNode& d, DeformedFieldOptions* o) {
                 if (d.IsSequence()) {
                   o->regions.clear();
                   for (const ConfigNode& e : d.Elements()) o->regions.push_back(ParseDomain(e));
                   if (o->regions.empty() || o->regions.size() > 64) d.Fail("needs 1 to 64 domains");
                 } else {
                   const long long n = d.AsInt();
                   if (n < 1 || n > 64) d.Fail("must be between 1 and 64, got " + d.Quoted());
                   o->domains = int(n);
                 }
               },
               HashDomains, [](const DeformedFieldOptions& o) { return std::to_string(o.domains); })
              .Sweepable()
              .Example("2"),
          P::Number("overlap", PARAM_MEMBER(overlap), AtLeast(0), NoUpperBound(), "by how much domains overlap")
              .Unit("m").Default("3 rest-field cells").Example("0.001"),
          P::Integer("seed", PARAM_MEMBER(seed), 0, std::numeric_limits<std::int32_t>::max(),
                     "seed of the proxy fitting and the clustering")
              .Example("5"),
          P::Mapped("force_at", PARAM_MEMBER(force_at),
                    std::vector<std::pair<std::string, DeformedFieldOptions::ForceAt>>{
                        {"nearest", DeformedFieldOptions::ForceAt::kNearestProxy},
                        {"weighted", DeformedFieldOptions::ForceAt::kWeightedProxies}},
                    "where a contact force acts on the deformation: the nearest proxy (the paper's), or the "
                    "query's k proxies by their weights")
              .Example("weighted"),
      },
      [](const ConfigNode& n, DeformedFieldOptions* o) {
        if (o->proxies < o->neighbours) {
          (n.Has("proxies") ? n.Get("proxies") : n).Fail("must be at least neighbours (" + std::to_string(o->neighbours) + ")");
        }
        if (o->regions.empty() && o->domains > 1 && o->domains > o->proxies / 2) {
          n.Get("domains").Fail("at most proxies / 2 = " + std::to_string(o->proxies / 2) + " automatic domains");
        }
      });
  return table;
}

const ParamTable<DeformableSpec>& DeformableParams() {
  using P = ParamRows<DeformableSpec>;
  static const ParamTable<DeformableSpec> table(
      "bodies[].deformable",
      "A reduced deformable model (sec. 4.1): reduced StVK or linear modal dynamics on a voxel tet mesh built from "
      "the body's field.",
      {
          P::Mapped("model", PARAM_MEMBER(kind),
                    std::vector<std::pair<std::string, ReducedModelKind>>{{"stvk", ReducedModelKind::kStVK},
                                                                          {"linear", ReducedModelKind::kLinear}},
                    "reduced StVK, or linear modal dynamics")
              .Shapes(kShapesReducedModel).Example("linear"),
          P::Integer("modes", PARAM_MEMBER(modes), 1, kMaxReducedModes, "r, the reduced coordinates")
              .Shapes(kShapesReducedModel).Sweepable().Example("3"),
          P::Integer("cells", PARAM_MEMBER(cells), 1, 256, "voxel cells of the tet mesh along the longest side")
              .Shapes(kShapesReducedModel).Sweepable().Example("5"),
          P::Number("E", PARAM_MEMBER(material.youngs_modulus), Above(0), NoUpperBound(), "Young's modulus")
              .Unit("Pa").Shapes(kShapesReducedModel).Example("2e6"),
          P::Number("nu", PARAM_MEMBER(material.poisson_ratio), Above(-1), Below(0.5), "Poisson's ratio")
              .Shapes(kShapesReducedModel).Example("0.3"),
          P::Number("rho", PARAM_MEMBER(material.density), Above(0), NoUpperBound(), "density")
              .Unit("kg/m^3").Shapes(kShapesReducedModel).Example("500"),
          P::Block("damping", [](auto& s) -> auto& { return s; }, DampingParams(), "Rayleigh damping {alpha, beta}"),
          P::Custom(
               "anchor", "none or block", "none, {below: [axis, value]}, {box: [x0, y0, z0, x1, y1, z1]}, {outside: [...]}",
               "vertices held fixed (body frame, metres, after scale and centring)",
               [](const ConfigNode& v, DeformableSpec* d) {
                 d->anchor = ParseAnchor(v);
                 d->anchor.source = v.Location();  // errors found when the model is built name it
               },
               [](const DeformableSpec& d, Hasher* h) { HashAnchor(d.anchor, h); },
               [](const DeformableSpec& d) { return d.anchor.anchored() ? d.anchor.Describe() : std::string("none"); })
              .Shapes(kShapesReducedModel)
              .Example("{below: [z, -0.001]}"),
          P::Mapped("coupling", PARAM_MEMBER(implicit_contact),
                    std::vector<std::pair<std::string, bool>>{{"implicit", true}, {"explicit", false}},
                    "implicit: the step takes the contact's reduced stiffness; explicit: the force alone (the "
                    "paper's order)")
              .Example("explicit"),
          P::Block("field", PARAM_MEMBER(field), DeformedFieldParams(), "a field body's deformed distance field"),
      });
  return table;
}

const ParamTable<BodySpec>& BodyParams() {
  return BuiltFromRegistry<ParamTable<BodySpec>>([] {
  using P = ParamRows<BodySpec>;
  constexpr unsigned kAll = kShapesField | kShapesPointshell | kShapesReducedModel;  // through the mesh's content
  std::vector<ParamRow<BodySpec>> rows = {
          P::Text("name", PARAM_MEMBER(name), "the body's name (default: its mesh)"),
          P::Custom("mesh", "text", "a file on the data search path, or a procedural shape \"sphere:0.05\"",
                    "the body's surface (required); Python's Scene.from_dict also takes a contactlab.Mesh",
                    [](const ConfigNode& v, BodySpec* b) {
                      b->mesh = v.AsString();
                      b->mesh_where = v.Location();
                    },
                    [](const BodySpec& b, Hasher* h) { h->Text(b.mesh); }, [](const BodySpec& b) { return b.mesh; })
              .Shapes(kAll)
              .Example("\"sphere:0.011,2\""),
          P::Number("scale", PARAM_MEMBER(scale), Above(0), NoUpperBound(), "file units to metres").Shapes(kAll).Example("1.1"),
          P::Boolean("center", PARAM_MEMBER(center), "move the bounding-box centre to the body origin")
              .Shapes(kAll)
              .Example("true"),
          P::Custom("pose", "pose", "[x, y, z, qw, qx, qy, qz] or {position, rotation | rotation_vector}",
                    "the body's pose in the world at the scene's start (its quaternion of unit length, within 1e-6)",
                    [](const ConfigNode& v, BodySpec* b) { b->pose = ParsePoseNode(v); }, nullptr,
                    [](const BodySpec&) { return std::string("identity"); })
              .Example("[0, 0, 0.1, 1, 0, 0, 0]"),
          P::Choice("role", PARAM_MEMBER(role), {"pointshell", "field", "both"},
                    "two bodies: pointshell (body A) or field (body B), different roles (required); many bodies "
                    "(`tool:`): what it may be in its pairs, pointshell, field or both (default both)"),
          P::Number("deformation_bound", PARAM_MEMBER(deformation_bound), AtLeast(0), NoUpperBound(),
                    "many bodies: how far a deformable body's surface may move, growing its broad-phase box")
              .Unit("m")
              .Default("a tenth of its largest half-extent; 0 when rigid")
              .Example("0.005"),
          P::Block("field", PARAM_MEMBER(field), FieldParams(), "its distance field"),
          P::Block("pointshell", PARAM_MEMBER(pointshell), PointshellParams(), "its pointshell"),
          P::Custom("deformable", "block", "see `bodies[].deformable`", "a reduced deformable model (absent: rigid)",
                    [](const ConfigNode& v, BodySpec* b) { b->deformable = DeformableParams().Parse(v); },
                    [](const BodySpec& b, Hasher* h) {
                      if (b.deformable) DeformableParams().Hash(*b.deformable, kShapesReducedModel, h);
                    },
                    [](const BodySpec&) { return std::string("absent"); })
              .Shapes(kShapesReducedModel),
  };
  // Each registered model's blocks, read into the body's model_blocks.
  for (const RegisteredBlock& r : RegisteredBlocks(true)) {
    ExpectNewKey(rows, r.block->key, "bodies[]", r.models);
    rows.push_back(P::Block(r.block->key, PARAM_MEMBER(model_blocks), *r.block->table, r.block->doc));
  }
  return ParamTable<BodySpec>(
      "bodies[]", "One of the scene's bodies: its mesh, placement, role, and the blocks that build its models.",
      std::move(rows),
      [](const ConfigNode& n, BodySpec* b) {
        (void)n.Get("mesh");  // required
        if (!n.Has("name")) b->name = b->mesh;
        if (b->deformable && b->field.storage == "sparse") {
          n.Get("field").Get("storage").Fail(
              "a deformable body needs a dense field (its reduced model and deformed field read every sample)");
        }
      });
  });
}

Pose ParsePoseNode(const ConfigNode& n) {
  if (n.IsSequence()) {
    const std::vector<double> v = n.AsDoubles();
    if (v.size() != 7) n.Fail("a pose list needs 7 numbers x, y, z, qw, qx, qy, qz");
    const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (const std::optional<std::string> e = NonUnitQuaternionError(q)) n.Fail(*e);
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
    const Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (const std::optional<std::string> e = NonUnitQuaternionError(q)) r->Fail(*e);
    pose.rotation = q.normalized();
  }
  if (auto r = n.Find("rotation_vector")) {
    const std::vector<double> v = r->AsDoubles();
    if (v.size() != 3) r->Fail("needs 3 numbers (axis times angle, radians)");
    pose.rotation = RotationFromVector(Eigen::Vector3d(v[0], v[1], v[2]));
  }
  return pose;
}

namespace {

// The index of the body NAME in SCENE, or -1.
int BodyIndex(const Scene& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].name == name) return int(i);
  }
  return -1;
}

// A scene of many bodies: the tool, the default pairs (the tool against every other body) and
// the scene's `pairs:`, which add pairs and override a default pair's model and parameters.
void ParseManyBodies(const ConfigNode& n, const std::vector<ConfigNode>& body_nodes, Scene* scene) {
  for (std::size_t i = 0; i < scene->bodies.size(); ++i) {
    BodySpec& b = scene->bodies[i];
    if (b.role.empty()) b.role = "both";
    for (std::size_t j = 0; j < i; ++j) {
      if (scene->bodies[j].name == b.name) {
        body_nodes[i].Fail("a second body named '" + b.name + "' (pairs and `tool` name bodies, so names are unique)");
      }
    }
  }
  if (!n.Has("tool")) {
    n.Get("bodies").Fail("a scene of " + std::to_string(scene->bodies.size()) +
                         " bodies names the body the device or the trajectory moves: tool: NAME");
  }
  const ConfigNode tool = n.Get("tool");
  scene->tool = BodyIndex(*scene, tool.AsString());
  if (scene->tool < 0) tool.Fail("'" + tool.AsString() + "' is none of the scene's bodies");
  const std::string file_where = scene->file.empty() ? std::string("scene") : scene->file;
  for (int i = 0; i < int(scene->bodies.size()); ++i) {
    if (i == scene->tool) continue;
    PairSpec p;
    p.bodies = {scene->tool, i};
    p.where = file_where + ": the tool against body '" + scene->bodies[std::size_t(i)].name + "'";
    scene->pairs.push_back(p);
  }
  if (auto ps = n.Find("pairs")) {
    std::vector<std::string> seen;
    for (const ConfigNode& e : ps->Elements()) {
      e.ExpectKeys({"bodies", "model", "params"});
      const ConfigNode names = e.Get("bodies");
      const std::vector<ConfigNode> two = names.Elements();
      if (two.size() != 2) names.Fail("a pair names two bodies, got " + std::to_string(two.size()));
      PairSpec p;
      for (int k = 0; k < 2; ++k) {
        p.bodies[std::size_t(k)] = BodyIndex(*scene, two[std::size_t(k)].AsString());
        if (p.bodies[std::size_t(k)] < 0) two[std::size_t(k)].Fail("'" + two[std::size_t(k)].AsString() + "' is none of the scene's bodies");
      }
      if (p.bodies[0] == p.bodies[1]) names.Fail("a pair of body '" + two[0].AsString() + "' with itself");
      const std::string key = std::to_string(std::min(p.bodies[0], p.bodies[1])) + "/" +
                              std::to_string(std::max(p.bodies[0], p.bodies[1]));
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
        names.Fail("the pair " + two[0].AsString() + " / " + two[1].AsString() + " is named twice");
      }
      seen.push_back(key);
      p.where = e.Location();
      if (auto m = e.Find("model")) {
        p.model = m->AsString();
        if (p.model != "none" && FindContactModel(p.model) == nullptr) {
          std::string known;
          for (const std::string& name : ContactModelNames()) known += (known.empty() ? "" : ", ") + name;
          m->Fail("unknown contact model '" + p.model + "' (known: " + known + ", none)");
        }
      }
      if (auto params = e.Find("params")) {
        if (params->Has("node_budget") || params->Has("warm_threshold")) {
          params->Fail("the node budget is the scene's, one for the cycle, shared by every pair (model.node_budget)");
        }
        const Scene own = WithModelSection(*scene, *params);
        p.has_params = true;
        p.params = own.model;
        p.model_params = own.model_params;
      }
      // A pair of the tool replaces its default pair; any other is added.
      auto same = [&](const PairSpec& q) {
        return (q.bodies[0] == p.bodies[0] && q.bodies[1] == p.bodies[1]) ||
               (q.bodies[0] == p.bodies[1] && q.bodies[1] == p.bodies[0]);
      };
      const auto it = std::find_if(scene->pairs.begin(), scene->pairs.end(), same);
      if (it != scene->pairs.end()) {
        *it = p;
      } else {
        scene->pairs.push_back(p);
      }
    }
  }
  scene->pairs.erase(std::remove_if(scene->pairs.begin(), scene->pairs.end(),
                                    [](const PairSpec& p) { return p.model == "none"; }),
                     scene->pairs.end());
  // Every pair's model takes its bodies in some order, for every model the scene compares.
  for (const PairSpec& p : scene->pairs) {
    const std::vector<std::string> names = p.model.empty() ? scene->models : std::vector<std::string>{p.model};
    for (const std::string& name : names) (void)OrderPair(*scene, p, name);
  }
  for (int i = 0; i < int(scene->bodies.size()); ++i) {
    const bool used = i == scene->tool || std::any_of(scene->pairs.begin(), scene->pairs.end(), [&](const PairSpec& p) {
                        return p.bodies[0] == i || p.bodies[1] == i;
                      });
    if (!used) {
      scene->warnings.push_back(body_nodes[std::size_t(i)].Location() + ": body '" + scene->bodies[std::size_t(i)].name +
                                "' is in no pair: nothing touches it");
    }
  }
}

}  // namespace

OrderedPair OrderPair(const Scene& scene, const PairSpec& pair, std::string_view default_model) {
  OrderedPair o;
  o.model = pair.model.empty() ? std::string(default_model) : pair.model;
  const ContactModelEntry* entry = FindContactModel(o.model);
  const BodySpec& first = scene.bodies[std::size_t(pair.bodies[0])];
  const BodySpec& second = scene.bodies[std::size_t(pair.bodies[1])];
  if (entry == nullptr) {
    Fail(pair.where, "unknown contact model '" + o.model + "' for the pair " + first.name + " / " + second.name);
  }
  const ContactModelNeeds& needs = entry->needs;
  auto may_be_A = [&](const BodySpec& b) { return b.role != "field" || !(needs.pointshell_A || needs.field_A); };
  auto may_be_B = [&](const BodySpec& b) { return b.role != "pointshell" || !needs.field_B; };
  const ContactParams& params = pair.has_params ? pair.params : scene.model;
  const ParamValues& model_params = pair.has_params ? pair.model_params : scene.model_params;
  for (const auto& [a, b] : {std::pair{0, 1}, std::pair{1, 0}}) {
    const BodySpec& A = scene.bodies[std::size_t(pair.bodies[std::size_t(a)])];
    const BodySpec& B = scene.bodies[std::size_t(pair.bodies[std::size_t(b)])];
    if (!may_be_A(A) || !may_be_B(B)) continue;
    CheckContactModel(o.model, params, model_params, A.name, A.deformable.has_value(), B.name, B.deformable.has_value(),
                      pair.where);
    o.A = pair.bodies[std::size_t(a)];
    o.B = pair.bodies[std::size_t(b)];
    return o;
  }
  Fail(pair.where, "model " + o.model + " needs a pointshell body and a field body, and neither of " + first.name +
                       " (role " + first.role + ") and " + second.name + " (role " + second.role +
                       ") can take the role it lacks");
}

Scene ParseScene(const ConfigNode& n) {
  RegisterContactModels();  // a scene names models and their keys: every model the build holds
  // An experiment config where a scene belongs (`contactlab contact CONFIG.yaml`): it names a
  // scene instead of holding bodies, and its keys would otherwise read as unknown scene keys.
  if (n.path().empty() && n.IsMap() && n.Has("scene") && !n.Has("bodies")) {
    Fail(n.file(), "this is an experiment config (it names a scene and has no bodies): use `contactlab run " +
                       n.file() + "` (a scene is a file like data/scenes/*.yaml)");
  }
  n.ExpectKeys({"name", "bodies", "model", "models", "tool", "pairs"});
  Scene scene;
  scene.file = n.file();
  scene.name = n.String("name", std::filesystem::path(n.file()).stem().string());
  const std::vector<ConfigNode> bodies = n.Get("bodies").Elements();
  const bool many = n.Has("tool") || n.Has("pairs") || bodies.size() > 2;
  if (bodies.size() < 2) n.Get("bodies").Fail("a scene needs at least two bodies, got " + std::to_string(bodies.size()));
  if (bodies.size() > std::size_t(kMaxSceneBodies)) {
    n.Get("bodies").Fail("a scene holds at most " + std::to_string(kMaxSceneBodies) + " bodies, got " +
                         std::to_string(bodies.size()));
  }
  for (const ConfigNode& b : bodies) scene.bodies.push_back(BodyParams().Parse(b));
  if (auto m = n.Find("model")) scene = ModelSectionParams().Parse(*m, scene);
  if (auto ms = n.Find("models")) {
    for (const ConfigNode& e : ms->Elements()) scene.models.push_back(e.AsString());
    if (scene.models.empty()) ms->Fail("lists no model");
  } else {
    scene.models = {"pointshell"};
  }
  if (many) {
    ParseManyBodies(n, bodies, &scene);
    // The two-body fields hold the tool as the haptic body H (field_body, as a session moves it)
    // and another body, for what reads a scene's poses and sizes (the haptic cycle's start pose
    // and coherence guard).
    scene.field_body = scene.bodies[std::size_t(scene.tool)];
    scene.pointshell_body = scene.bodies[std::size_t(scene.tool == 0 ? 1 : 0)];
    return scene;
  }
  BodySpec a = scene.bodies[0];
  BodySpec b = scene.bodies[1];
  for (int i = 0; i < 2; ++i) {
    const std::string& role = scene.bodies[std::size_t(i)].role;
    if (role.empty()) (void)bodies[std::size_t(i)].Get("role");  // required
    if (role == "both") {
      bodies[std::size_t(i)].Get("role").Fail("'both' is for a scene of many bodies (with `tool:`); a body of a "
                                               "two-body scene is its pointshell or its field");
    }
  }
  if (a.role == b.role) bodies[1].Get("role").Fail("the two bodies need different roles (one pointshell, one field)");
  if (a.role == "field") std::swap(a, b);
  scene.pointshell_body = a;
  scene.field_body = b;
  scene.bodies.clear();  // a two-body scene's bodies are pointshell_body and field_body, which sweeps change
  return scene;
}

Scene LoadScene(const std::filesystem::path& file) { return ParseScene(ConfigNode::LoadFile(file)); }

Scene WithModelSection(Scene scene, const ConfigNode& node) { return ModelSectionParams().Parse(node, std::move(scene)); }

std::vector<const BodySpec*> Scene::AllBodies() const {
  if (!many_bodies()) return {&pointshell_body, &field_body};
  std::vector<const BodySpec*> all;
  for (const BodySpec& b : bodies) all.push_back(&b);
  return all;
}

void Scene::RequireTwoBodies(std::string_view what) const {
  if (!many_bodies()) return;
  Fail(file.empty() ? std::string("scene") : file,
       std::string(what) + " takes a scene of two bodies; this one has " + std::to_string(bodies.size()) +
           " bodies and a tool (`contactlab contact` queries every pair of it)");
}

Scene Scene::Swapped() const {
  Scene s = *this;
  std::swap(s.pointshell_body, s.field_body);
  s.pointshell_body.role = "pointshell";
  s.field_body.role = "field";
  s.name = name + " (roles swapped)";
  return s;
}

namespace {

// The value of KEY of TABLE's block SPEC, as the reference shows it.
template <class Spec>
std::string ShowKey(const ParamTable<Spec>& table, const Spec& spec, const std::string& key) {
  const ParamRow<Spec>* row = table.Find(key);
  return row ? row->show(spec) : std::string();
}

// A block every body carries, KEY in the scene, MEMBER of BodySpec, parsed by TABLE: two scene
// blocks, the field body's (its keys sweep alone; the reference shows its table) and the
// pointshell body's (its keys sweep with the prefix "pointshell_").
template <class Spec>
std::array<SceneBlock, 2> EveryBodyBlock(const std::string& key, const ParamTable<Spec>& table,
                                         std::type_identity_t<const Spec& (*)(const BodySpec&)> member) {
  return {SceneBlock{"scene.bodies[role=field]." + key + ".", "", table.SweepKeys(), table.Reference("bodies[]." + key),
                     [&table, member](const Scene& s, const std::string& k) {
                       return ShowKey(table, member(s.field_body), k);
                     }},
          SceneBlock{"scene.bodies[role=pointshell]." + key + ".", "pointshell_", table.SweepKeys(), "",
                     [&table, member](const Scene& s, const std::string& k) {
                       return ShowKey(table, member(s.pointshell_body), k);
                     }}};
}

}  // namespace

const std::vector<SceneBlock>& SceneBlocks() {
  const auto none = [](const Scene&, const std::string&) { return std::string(); };
  return BuiltFromRegistry<std::vector<SceneBlock>>([&] {
    std::vector<SceneBlock> b;
    const auto add = [&b](std::array<SceneBlock, 2> both) { b.insert(b.end(), both.begin(), both.end()); };
    b.push_back({"", "", {}, BodyParams().Reference("bodies[]"), none});
    add(EveryBodyBlock("field", FieldParams(), [](const BodySpec& body) -> const FieldSpec& { return body.field; }));
    b.insert(b.end(), {
      {"scene.bodies[role=pointshell].pointshell.", "", PointshellParams().SweepKeys(),
       PointshellParams().Reference("bodies[].pointshell"),
       [](const Scene& s, const std::string& k) { return ShowKey(PointshellParams(), s.pointshell_body.pointshell, k); }},
      {"scene.bodies[role=pointshell].deformable.", "", DeformableParams().SweepKeys(),
       DeformableParams().Reference("bodies[].deformable"),
       [](const Scene& s, const std::string& k) {
         return s.pointshell_body.deformable ? ShowKey(DeformableParams(), *s.pointshell_body.deformable, k)
                                             : std::string();
       }},
      {"", "", {}, DampingParams().Reference("bodies[].deformable.damping"), none},
      {"scene.bodies[role=field].deformable.field.", "", DeformedFieldParams().SweepKeys(),
       DeformedFieldParams().Reference("bodies[].deformable.field"),
       [](const Scene& s, const std::string& k) {
         return s.field_body.deformable ? ShowKey(DeformedFieldParams(), s.field_body.deformable->field, k)
                                        : std::string();
       }},
    });
    for (const RegisteredBlock& r : RegisteredBlocks(true)) {
      add(EveryBodyBlock(r.block->key, *r.block->table,
                         [](const BodySpec& body) -> const ParamValues& { return body.model_blocks; }));
    }
    b.push_back(
      {"scene.model.", "", ModelSectionParams().SweepKeys(), ModelSectionParams().Reference("model"),
       [](const Scene& s, const std::string& k) { return ShowKey(ModelSectionParams(), s, k); }});
    b.push_back({"scene.model.friction.", "friction_", FrictionParamTable().SweepKeys(),
                 FrictionParamTable().Reference("model.friction", {}, "friction_"), [](const Scene& s, const std::string& k) {
                   return ShowKey(FrictionParamTable(), s.model.friction, k);
                 }});
    return b;
  });
}

std::string SceneReference() {
  // The scene's top-level keys, and the pairs of a scene of many bodies (ParseManyBodies).
  std::string s =
      "### scene\n\nThe top-level keys of a scene file (docs/scenes.md; \"Many bodies\" for `tool` and `pairs`).\n\n"
      "| key | value | meaning |\n|---|---|---|\n"
      "| `name` | text (default: the file's stem) | the scene's name |\n"
      "| `bodies` | list of `bodies[]` blocks, 2 to " + std::to_string(kMaxSceneBodies) +
      " | the bodies; two without `tool`: one pointshell, one field |\n"
      "| `tool` | a body's name | the body the device or the trajectory moves; makes it a scene of many bodies, "
      "required beyond two bodies |\n"
      "| `pairs` | list of `pairs[]` blocks | pairs beside the default ones (the tool against every other body), "
      "or a default pair's model and parameters |\n"
      "| `model` | the `model` block | the models' parameters, every pair's unless it gives its own |\n"
      "| `models` | list of model names (default: pointshell) | the contact models to compare (a pair without a "
      "model of its own takes each in turn) |\n\n"
      "### `pairs[]`\n\nA pair of a scene of many bodies: two bodies that may touch, and the model between them.\n\n"
      "| key | value | meaning |\n|---|---|---|\n"
      "| `bodies` | two body names (required) | the pair; taken in its model's A/B order: as written when each body "
      "may take its role (`bodies[].role`), else exchanged |\n"
      "| `model` | a registered model, or none (default: the model compared) | the pair's model; none removes a "
      "default pair |\n"
      "| `params` | a `model` block without node_budget | the pair's own model parameters, replacing the "
      "scene's (the node budget is the cycle's, shared by every pair) |\n\n";
  for (const SceneBlock& b : SceneBlocks()) s += b.reference;
  return s;
}

}  // namespace contactlab
