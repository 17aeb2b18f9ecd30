// The preprocessed data of a scene's bodies: meshes in metres, distance fields and
// pointshells, built on demand and cached on disk keyed by everything they depend on, so a
// second run does not rebuild them.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "contact/model_registry.h"
#include "deform/body_dynamics.h"
#include "deform/deformable_pointshell.h"
#include "deform/deformed_distance_field.h"
#include "deform/reduced_integrator.h"
#include "deform/reduced_model.h"
#include "scene/scene.h"
#include "geometry/triangle_mesh.h"
#include "pointshell/build_pointshell.h"
#include "pointshell/pointshell.h"
#include "sdf/build_distance_field.h"
#include "sdf/distance_field.h"
#include "util/data_path.h"

namespace contactlab {

// The builder versions that enter the cache keys: a cached field, pointshell or reduced model
// is found only under the versions of the builders it came from (a pointshell or reduced model
// also depends on the field's). Version 1 adds nothing to a key, so entries cached before
// versions existed stay valid. Tests set other values; programs keep the defaults.
struct BuilderVersions {
  int field = kDistanceFieldBuilderVersion;
  int pointshell = kPointshellBuilderVersion;
  int reduced_model = kReducedModelBuilderVersion;
};

struct AssetOptions {
  std::filesystem::path cache_dir;  // empty: DefaultCacheDir()
  bool use_cache = true;            // read and write cached fields and pointshells
  bool verbose = true;              // say on stderr what is built or reused
  std::filesystem::path mesh_dir;   // searched first for mesh files (the scene file's folder)
  BuilderVersions builders;         // versions in the cache keys
};

// $CONTACTLAB_CACHE, else $XDG_CACHE_HOME/contactlab, else $HOME/.cache/contactlab, else
// a folder under the system temp dir.
std::filesystem::path DefaultCacheDir();

// Reads a body's mesh: a file through the data search path, or a procedural shape written
// "sphere:R[,subdivisions]", "box:HX,HY,HZ", "torus:MAJOR,MINOR", "capsule:R,HALF_LENGTH",
// "bumpy-plate:SIZE,THICKNESS,BUMPS,HEIGHT[,RESOLUTION]" (metres; scale still applies).
// A body with mesh_data takes that in-memory mesh instead (BodySpec). Applies the body's scale
// and centring. MESH_DIR (the scene file's folder) is searched before the rest of the data
// search path. Throws Error naming the body and the mesh.
TriangleMesh LoadBodyMesh(const BodySpec& body, const std::filesystem::path& mesh_dir = {});

// One scene body's data for the contact models (contact/model_registry.h ContactBody),
// built on first use and cached.
class BodyAssets final : public ContactBody {
 public:
  BodyAssets(BodySpec spec, AssetOptions options);

  const BodySpec& spec() const { return spec_; }
  std::string_view body_name() const override { return spec_.name; }
  std::shared_ptr<const TriangleMesh> mesh() override;
  std::shared_ptr<const DistanceField> field() override;
  std::shared_ptr<const Pointshell> pointshell() override;
  std::uint64_t sampling_seed() const override { return spec_.pointshell.seed; }
  // The body's reduced deformable model (paper sec. 4.1): the voxel tet mesh of its field at
  // spec().deformable->cells, anchored and reduced as the spec says; body frame, metres.
  // Cached like fields, keyed by the mesh content, the field's and every deformable
  // parameter. Throws Error naming the body when it has no deformable block.
  std::shared_ptr<const ReducedModel> reduced_model();
  bool deformable() const override { return spec_.deformable.has_value(); }
  // The body's pointshell embedded in its reduced model (built in memory on first use).
  std::shared_ptr<const DeformablePointshell> deformable_pointshell() override;
  // The body's deformed distance field (paper sec. 4.2): proxies fitted to its field, embedded
  // in its reduced model, with the scene's deformable.field options (built in memory).
  std::shared_ptr<const DeformedDistanceField> deformed_field() override;
  const ParamValues& model_blocks() const override { return spec_.model_blocks; }
  // OPTIONS' cache folder / "derived-HASH.bin", HASH of the field's key and KEY; empty when
  // caching is off.
  std::filesystem::path DerivedCachePath(std::string_view key) override;
  // A key of the mesh content and load parameters (hex), part of every cache key.
  const std::string& mesh_key();
  // What has been built or read so far, of: mesh, field, pointshell, reduced model, deformable
  // pointshell, deformed field (what a scene's models needed of the body).
  std::vector<std::string> Built() const;

 private:
  BodySpec spec_;
  AssetOptions options_;
  std::shared_ptr<const TriangleMesh> mesh_;
  std::shared_ptr<const DistanceField> field_;
  std::shared_ptr<const Pointshell> pointshell_;
  std::shared_ptr<const ReducedModel> reduced_model_;
  std::shared_ptr<const DeformablePointshell> deformable_pointshell_;
  std::shared_ptr<const DeformedDistanceField> deformed_field_;
  std::string mesh_key_;
  std::string field_key_;  // the field's cache key (hex), set by field()
};

// Body A (pointshell role) and body B (field role) of a scene.
struct SceneAssets {
  // Mesh names are looked up first beside the scene's file (unless OPTIONS names a folder).
  SceneAssets(const Scene& scene, const AssetOptions& options = {})
      : A(scene.pointshell_body, WithMeshDir(options, scene)), B(scene.field_body, WithMeshDir(options, scene)) {}
  BodyAssets A;
  BodyAssets B;

 private:
  static AssetOptions WithMeshDir(AssetOptions options, const Scene& scene) {
    if (options.mesh_dir.empty() && !scene.file.empty()) options.mesh_dir = FolderOf(scene.file);
    return options;
  }
};

// The time stepping of a deformable body at the haptic cycle DT (seconds): its Rayleigh damping.
IntegratorOptions DeformableIntegratorOptions(const DeformableSpec& deformable, double dt);

// The dynamics of BODY at the haptic cycle DT (seconds): its reduced model (built or read from
// the cache), stepped as its deformable block says (DeformableIntegratorOptions, its coupling
// mode); STAGGERED: the other body deforms too. Null for a rigid body. Throws Error naming the
// body for a non-positive DT.
std::unique_ptr<BodyDynamics> MakeBodyDynamics(BodyAssets& body, double dt, bool staggered);

// The dynamics of a scene's two bodies: null for a rigid one; when both deform, both step
// staggered. What the runner, the live session and the closed-loop study step.
struct SceneDynamics {
  std::unique_ptr<BodyDynamics> A;  // the pointshell body's
  std::unique_ptr<BodyDynamics> B;  // the field body's (in a haptic loop: the haptic body H)
  bool any() const { return A != nullptr || B != nullptr; }
  // Both back to rest.
  void Reset() {
    if (A) A->Reset();
    if (B) B->Reset();
  }
};
SceneDynamics MakeSceneDynamics(SceneAssets& assets, double dt);

// Makes the registered contact model NAME between SCENE's bodies, with the scene's model
// parameters; only what the model needs is built. Under `model.stiffness: matched` a model
// other than the paper's comes scaled to the paper's model's stiffness (stiffness_match.h;
// WrenchScaleOf says by how much). Throws Error naming the scene file when NAME is unknown.
std::unique_ptr<ContactModel> MakeSceneContactModel(std::string_view name, const Scene& scene, SceneAssets& assets);

}  // namespace contactlab
