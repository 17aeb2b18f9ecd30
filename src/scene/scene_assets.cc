#include "scene/scene_assets.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "contact/register_contact_models.h"
#include "scene/stiffness_match.h"
#include "geometry/mesh_from_arrays.h"
#include "geometry/mesh_io.h"
#include "geometry/procedural_shapes.h"
#include "pointshell/build_pointshell.h"
#include "pointshell/pointshell_io.h"
#include "sdf/build_distance_field.h"
#include "util/cached_or_built.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/hasher.h"
#include "util/parse_number.h"

namespace contactlab {
namespace fs = std::filesystem;
namespace {

// Bumped whenever a builder changes what it produces, so stale cache entries are not reused.
constexpr const char* kCacheGeneration = "3";

TriangleMesh MakeShape(const std::string& spec, const std::string& where) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::vector<double> a = ParseNumberList(spec.substr(colon + 1), where);
  auto need = [&](std::size_t lo, std::size_t hi) {
    if (a.size() < lo || a.size() > hi) {
      Fail(where, "shape '" + kind + "' takes " + std::to_string(lo) + (lo == hi ? "" : " to " + std::to_string(hi)) +
                      " numbers, got " + std::to_string(a.size()));
    }
  };
  // Number I, a count of the shape's: a whole number in [LO, HI] (bounded so that no shape
  // passes about 5 million triangles), FALLBACK when absent. 2.9 cuts were once taken for 2, and
  // 20,000 hung the build.
  auto count = [&](std::size_t i, int fallback, int lo, int hi, const char* what) {
    if (i >= a.size()) return fallback;
    if (!(a[i] >= lo && a[i] <= hi && a[i] == std::floor(a[i]))) {
      char text[200];
      std::snprintf(text, sizeof text, "shape '%s': %s must be a whole number in [%d, %d], got %.10g", kind.c_str(), what,
                    lo, hi, a[i]);
      Fail(where, text);
    }
    return int(a[i]);
  };
  TriangleMesh m;
  if (kind == "sphere") {
    need(1, 2);
    m = MakeSphere(a[0], count(1, 5, 0, 9, "its subdivisions (20 * 4^n triangles)"));
  } else if (kind == "box") {
    need(3, 4);
    m = MakeBox(Eigen::Vector3d(a[0], a[1], a[2]), count(3, 8, 1, 512, "its cuts per edge (12 n^2 triangles)"));
  } else if (kind == "torus") {
    need(2, 2);
    m = MakeTorus(a[0], a[1], 128, 64);
  } else if (kind == "capsule") {
    need(2, 2);
    m = MakeCapsule(a[0], a[1], 64, 16);
  } else if (kind == "tube") {
    need(3, 4);
    m = MakeTube(a[0], a[1], a[2], count(3, 96, 3, 1 << 19, "its segments around (8 n triangles)"));
  } else if (kind == "bumpy-plate") {
    need(4, 5);
    const int resolution = count(4, 128, 2, 1024, "its resolution (quads per side)");
    m = MakeBumpyPlate(a[0], a[1], count(2, 0, 0, resolution, "its bumps per side (at most the resolution)"), a[3],
                       resolution);
  } else {
    Fail(where, "unknown procedural shape '" + kind + "' (sphere, box, torus, capsule, tube, bumpy-plate)");
  }
  m.name = spec;
  return m;
}

}  // namespace

fs::path DefaultCacheDir() {
  if (const char* c = std::getenv("CONTACTLAB_CACHE"); c && *c) return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "contactlab";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "contactlab";
  return fs::temp_directory_path() / "contactlab-cache";
}

namespace {

// Fails naming WHERE when a coordinate of MESH (placed: scaled and centred) exceeds kMaxCoordinate.
void CheckPlacedMesh(const TriangleMesh& mesh, const std::string& where) {
  double largest = 0;
  for (const Eigen::Vector3d& p : mesh.vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (!(largest <= kMaxCoordinate)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "coordinates out of range: |coordinate| reaches %.3g m after scaling (the limit is %.0e m)",
                  largest, kMaxCoordinate);
    Fail(where, buf);
  }
}

}  // namespace

TriangleMesh LoadBodyMesh(const BodySpec& body, const fs::path& mesh_dir) {
  const std::string where = "body '" + body.name + "'";
  // Errors name the scene file (or "<dict>"), line and key when the body came from a scene.
  const std::string mesh_where = body.mesh_where.empty() ? where + " mesh" : body.mesh_where;
  TriangleMesh mesh;
  if (body.mesh_data) {
    // An in-memory mesh, checked as the readers check a file (geometry/mesh_from_arrays.h), placed
    // as LoadMesh places a file's: p <- s p - c (c the scaled box centre), nothing done at scale 1
    // without centring, so the same mesh from arrays and from a file has the same vertices, bit
    // for bit, and the same cache key.
    const std::string data_where = mesh_where + ": mesh '" + QuoteToken(body.mesh_data->name) + "'";
    CheckMeshContent(*body.mesh_data, data_where);
    mesh = *body.mesh_data;
    const double s = body.scale;
    const Eigen::Vector3d c = body.center ? Eigen::Vector3d(s * mesh.Bounds().center()) : Eigen::Vector3d::Zero();
    if (s != 1.0 || body.center) {
      for (Eigen::Vector3d& p : mesh.vertices) p = s * p - c;
    }
    CheckPlacedMesh(mesh, data_where);
    return mesh;
  }
  const bool procedural = body.mesh.find(':') != std::string::npos && !FindDataFile(body.mesh, mesh_dir);
  if (procedural) {
    const std::string shape_where = mesh_where + ": '" + QuoteToken(body.mesh) + "'";
    try {
      mesh = MakeShape(body.mesh, shape_where);
    } catch (const Error& e) {
      const std::string what = e.what();
      if (what.rfind(shape_where, 0) == 0) throw;
      Fail(shape_where, what);  // from geometry/procedural_shapes: "MakeSphere: needs radius > 0 ..."
    }
    if (body.center) {
      const Eigen::Vector3d c = mesh.Bounds().center();
      mesh.Transform(1.0, Eigen::Matrix3d::Identity(), -c);
    }
    mesh.Transform(body.scale, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    CheckPlacedMesh(mesh, shape_where);
  } else {
    MeshLoadOptions options;
    options.scale = body.scale;
    options.center = body.center;
    mesh = LoadMesh(RequireDataFile(body.mesh, mesh_dir), options);
  }
  return mesh;
}

BodyAssets::BodyAssets(BodySpec spec, AssetOptions options) : spec_(std::move(spec)), options_(std::move(options)) {
  if (options_.cache_dir.empty()) options_.cache_dir = DefaultCacheDir();
}

std::shared_ptr<const TriangleMesh> BodyAssets::mesh() {
  if (!mesh_) mesh_ = std::make_shared<const TriangleMesh>(LoadBodyMesh(spec_, options_.mesh_dir));
  return mesh_;
}

const std::string& BodyAssets::mesh_key() {
  if (mesh_key_.empty()) {
    const auto m = mesh();
    Hasher h;
    h.Text(kCacheGeneration);
    h.Bytes(m->vertices.data(), m->vertices.size() * sizeof(Eigen::Vector3d));
    h.Bytes(m->triangles.data(), m->triangles.size() * sizeof(Eigen::Vector3i));
    mesh_key_ = h.Hex();
  }
  return mesh_key_;
}

namespace {

// The cache file NAME in OPTIONS' cache folder, or empty (no cache) when caching is off.
fs::path CacheFile(const AssetOptions& options, const std::string& name) {
  return options.use_cache ? options.cache_dir / name : fs::path();
}

// A builder's version in a cache key; version 1 adds nothing (AssetOptions::builders).
void HashBuilderVersion(const char* builder, int version, Hasher* h) {
  if (version == 1) return;
  h->Text(builder);
  h->Value(version);
}

}  // namespace

std::shared_ptr<const DistanceField> BodyAssets::field() {
  if (field_) return field_;
  const FieldSpec& f = spec_.field;
  Hasher h;
  h.Text(mesh_key());
  h.Text("field");
  FieldParams().Hash(f, kShapesField, &h);
  HashBuilderVersion("field-builder", options_.builders.field, &h);
  field_key_ = h.Hex();
  field_ = CachedOrBuilt<DistanceField>(
      CacheFile(options_, "field-" + h.Hex() + ".sdf"), options_.verbose,
      "the " + std::to_string(f.resolution) + "-cell field of " + spec_.name, LoadDistanceField, SaveDistanceField,
      [&] {
        DistanceFieldOptions o;
        o.resolution = f.resolution;
        o.mode = ParseFieldMode(f.mode, "body '" + spec_.name + "' field.mode");
        o.padding = f.padding;
        o.soup_offset = f.offset;
        o.storage = ParseFieldStorage(f.storage, "body '" + spec_.name + "' field.storage");
        o.band_voxels = f.band;
        return BuildDistanceField(*mesh(), o);
      });
  // A mesh with holes is not refused in mode auto: it silently takes the polygon-soup pipeline,
  // whose surface is an offset band around the triangles, so contact starts early and the
  // forces differ from a closed mesh's. Said every time the field is used, built or cached.
  if (f.mode == "auto" && field_->info().mode == "soup") {
    std::fprintf(stderr,
                 "warning: body '%s' (mesh %s) is not watertight: its distance field is the polygon-soup one, "
                 "whose surface lies %.3g m outside the triangles, so contact starts that far out and forces "
                 "differ from a closed mesh's; close the mesh (`contactlab mesh-info` counts its holes), or set "
                 "field.mode: soup to choose this\n",
                 spec_.name.c_str(), spec_.mesh.c_str(), field_->info().offset);
  }
  return field_;
}

fs::path BodyAssets::DerivedCachePath(std::string_view key) {
  if (!options_.use_cache) return {};
  (void)field();
  Hasher h;
  h.Text(field_key_);
  h.Text(std::string(key));
  std::error_code ec;
  fs::create_directories(options_.cache_dir, ec);
  return options_.cache_dir / ("derived-" + h.Hex() + ".bin");
}

std::shared_ptr<const Pointshell> BodyAssets::pointshell() {
  if (pointshell_) return pointshell_;
  const PointshellSpec& s = spec_.pointshell;
  const auto f = field();
  Hasher h;
  h.Text(mesh_key());
  h.Text("pointshell");
  FieldParams().Hash(spec_.field, kShapesPointshell, &h);
  PointshellParams().Hash(s, kShapesPointshell, &h);
  HashBuilderVersion("field-builder", options_.builders.field, &h);
  HashBuilderVersion("pointshell-builder", options_.builders.pointshell, &h);
  pointshell_ = CachedOrBuilt<Pointshell>(
      CacheFile(options_, "pointshell-" + h.Hex() + ".ps"), options_.verbose,
      "the " + std::to_string(s.points) + "-point pointshell of " + spec_.name, LoadPointshell, SavePointshell, [&] {
        PointshellOptions o;
        o.method = ParsePointshellMethod(s.method, "body '" + spec_.name + "' pointshell.method");
        o.num_points = s.points;
        o.num_levels = s.levels;
        o.seed = s.seed;
        if (s.offset >= 0) o.offset = s.offset;
        return BuildPointshell(*f, o, mesh().get());
      });
  return pointshell_;
}

std::shared_ptr<const ReducedModel> BodyAssets::reduced_model() {
  if (reduced_model_) return reduced_model_;
  if (!spec_.deformable) Fail("body '" + spec_.name + "'", "is rigid (it has no deformable block)");
  const DeformableSpec& d = *spec_.deformable;
  const auto f = field();
  Hasher h;
  h.Text(mesh_key());
  h.Text("reduced-model");
  FieldParams().Hash(spec_.field, kShapesReducedModel, &h);
  DeformableParams().Hash(d, kShapesReducedModel, &h);
  HashBuilderVersion("field-builder", options_.builders.field, &h);
  HashBuilderVersion("reduced-model-builder", options_.builders.reduced_model, &h);
  const std::string where = "body '" + spec_.name + "' deformable";
  reduced_model_ = CachedOrBuilt<ReducedModel>(
      CacheFile(options_, "reduced-" + h.Hex() + ".rm"), options_.verbose,
      "the r = " + std::to_string(d.modes) + " reduced model of " + spec_.name, LoadReducedModel, SaveReducedModel,
      [&] {
        VoxelMeshOptions vo;
        vo.cells = d.cells;
        ReducedModelOptions o;
        o.modes = d.modes;
        o.kind = d.kind;
        o.material = d.material;
        o.anchoring = d.anchor;
        o.show_progress = options_.verbose;
        return BuildReducedModel(BuildVoxelTetMesh(*f, vo), o, where);
      });
  return reduced_model_;
}

std::shared_ptr<const DeformablePointshell> BodyAssets::deformable_pointshell() {
  if (!deformable_pointshell_) {
    const auto model = reduced_model();
    deformable_pointshell_ = std::make_shared<const DeformablePointshell>(pointshell(), model->mesh, model->basis);
  }
  return deformable_pointshell_;
}

std::shared_ptr<const DeformedDistanceField> BodyAssets::deformed_field() {
  if (!deformed_field_) {
    const auto model = reduced_model();
    if (options_.verbose) std::cerr << "building the deformed distance field of body '" << spec_.name << "'\n";
    deformed_field_ = std::make_shared<const DeformedDistanceField>(field(), model->mesh, model->basis,
                                                                    spec_.deformable->field, "body '" + spec_.name + "'");
  }
  return deformed_field_;
}

std::vector<std::string> BodyAssets::Built() const {
  std::vector<std::string> built;
  if (mesh_) built.push_back("mesh");
  if (field_) built.push_back("field");
  if (pointshell_) built.push_back("pointshell");
  if (reduced_model_) built.push_back("reduced model");
  if (deformable_pointshell_) built.push_back("deformable pointshell");
  if (deformed_field_) built.push_back("deformed field");
  return built;
}

IntegratorOptions DeformableIntegratorOptions(const DeformableSpec& deformable, double dt) {
  IntegratorOptions o;
  o.time_step = dt;
  o.mass_damping = deformable.mass_damping;
  o.stiffness_damping = deformable.stiffness_damping;
  return o;
}

std::unique_ptr<BodyDynamics> MakeBodyDynamics(BodyAssets& body, double dt, bool staggered) {
  if (!body.deformable()) return nullptr;
  const DeformableSpec& d = *body.spec().deformable;
  IntegratorOptions options = DeformableIntegratorOptions(d, dt);
  options.Validate("body '" + body.spec().name + "' dynamics");
  return std::make_unique<BodyDynamics>(body.reduced_model(), options, d.implicit_contact, staggered);
}

SceneDynamics MakeSceneDynamics(SceneAssets& assets, double dt) {
  const bool both = assets.A.deformable() && assets.B.deformable();
  SceneDynamics d;
  d.A = MakeBodyDynamics(assets.A, dt, both);
  d.B = MakeBodyDynamics(assets.B, dt, both);
  return d;
}

std::unique_ptr<ContactModel> MakeSceneContactModel(std::string_view name, const Scene& scene, SceneAssets& assets) {
  RegisterContactModels();
  return ApplyStiffnessRule(MakeContactModel(name, ContactModelInputs{assets.A, assets.B, scene.model, scene.model_params},
                                             scene.file.empty() ? std::string_view("scene") : std::string_view(scene.file)),
                            name, scene, assets);
}

}  // namespace contactlab
