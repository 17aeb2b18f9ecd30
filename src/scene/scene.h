// Scenes: bodies and the parameters of the contact models that act between them, read from
// YAML. A scene of two bodies is written as below; a scene of many bodies (docs/scenes.md,
// "Many bodies") names its tool and lists its pairs:
//
//   tool: part                    # the body the device or the trajectory moves
//   pairs:                        # default: the tool against every other body
//     - {bodies: [hose1, hose2], model: pointshell}            # a pair between two others
//     - {bodies: [part, bracket], model: fcl, params: {k_C: 500}}  # a default pair's model
//     - {bodies: [part, frame], model: none}                   # no pair
//
// A two-body scene: Body "pointshell" (A) carries the pointshell, body "field" (B) the distance
// field; either may carry both so roles can be swapped in experiments.
//
//   name: dragon-on-bunny
//   bodies:
//     - name: dragon
//       mesh: dragon.obj          # data search path, or a procedural shape "sphere:0.05"
//       scale: 0.001              # file units -> metres
//       center: true              # move the bounding-box centre to the body origin
//       pose: [x, y, z, qw, qx, qy, qz]
//       role: pointshell          # pointshell | field
//       pointshell: {points: 16000, levels: 4, method: repulsion, seed: 1, offset: 0}
//       field: {resolution: 128, mode: auto}
//       pressure_field: {modulus: 1e5}   # pressure-field model: E (Pa), or {rigid: true}
//       inner_spheres: {spheres: 2000}   # inner-spheres model: its packing (count, coverage)
//       deformable:               # optional: a reduced deformable model (paper sec. 4.1)
//         model: stvk             # stvk | linear (modal)
//         modes: 15               # r
//         cells: 16               # voxel cells of the coarse tet mesh along the longest side
//         E: 1e6                  # Young's modulus, Pa
//         nu: 0.45                # Poisson's ratio
//         rho: 1000               # density, kg/m^3
//         damping: {alpha: 0, beta: 0}   # Rayleigh: D = alpha M + beta K
//         anchor: {below: [y, -0.02]}    # or {box: [x0, y0, z0, x1, y1, z1]}, or none
//                                 # (body frame, metres, after scale and centring)
//         field: {proxies: 40, neighbours: 5, domains: 3}  # a field body's deformed field
//                                 # (paper sec. 4.2); domains: a count (automatic) or a list
//                                 # of {box: [...]} / {halfspace: [nx, ny, nz, c]}
//     - name: bunny
//       ...
//       role: field
//   model: {k_C: 2000, L: 10, node_budget: 0, max_point_speed: 1.0, coherence: true, ...}
//
// The model section is the keys every model shares (contact/contact_params.h), node_budget
// (alias warm_threshold), the warm threshold V_W handed to each query, and each registered
// model's own keys (ContactModelEntry::pair_params: the paper's level, pointshell-ccd's proxy_*,
// ...). A body's blocks beyond field, pointshell and deformable are the registered models'
// (ContactModelEntry::body_blocks: pressure_field, inner_spheres, ...).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_params.h"
#include "deform/anchoring.h"
#include "deform/deformed_distance_field.h"
#include "deform/reduced_forces.h"
#include "reduced/reduced_state.h"
#include "deform/stvk_fem.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"
#include "util/config_node.h"
#include "util/param_table.h"
#include "util/param_values.h"

namespace contactlab {

// Upper limits on the sizes a scene may ask for, checked when parsing so that a typo such as
// "points: 10000000000" is a clear error naming the key, not an allocation failure minutes later.
inline constexpr int kMaxFieldResolution = 1024;       // cells along the longest side
inline constexpr int kMaxPointshellPoints = 1 << 24;   // 16,777,216 points
inline constexpr int kMaxPointshellLevels = 12;        // tree levels
inline constexpr int kMaxSceneBodies = 1024;           // bodies of one scene

struct FieldSpec {
  int resolution = 64;        // cells along the longest side
  std::string mode = "auto";  // auto | closed | soup
  double padding = 0.1;       // fraction of the largest extent
  double offset = -1;         // soup iso-offset, metres (< 0: the builder's default)
  std::string storage = "dense";  // dense | sparse (a fine band over a 1/8-resolution field)
  int band = 3;               // sparse: voxels of fine samples on each side of the surface
};

struct PointshellSpec {
  int points = 4096;                 // points on the deepest level
  int levels = 4;                    // tree levels
  std::string method = "repulsion";  // repulsion | voxel | vertices | random
  std::uint64_t seed = 1;
  double offset = -1;                // level-set offset delta, metres (< 0: builder's default)
};

// A body's reduced deformable model: reduced StVK or linear modal dynamics on a voxel tet mesh
// built from the body's field (paper sec. 4.1). Defaults are those of deform/.
struct DeformableSpec {
  ReducedModelKind kind = ReducedModelKind::kStVK;
  int modes = 15;                    // r
  int cells = 16;                    // voxel cells along the longest side
  StVKMaterial material;             // E, nu, rho
  double mass_damping = 0;           // Rayleigh alpha, 1/s
  double stiffness_damping = 0;      // Rayleigh beta, s
  Anchoring anchor;                  // free unless given
  // coupling: implicit (default) gives the integrator the contact's reduced stiffness, so the
  // step treats the penalty force linearly implicitly; explicit applies the force alone, the
  // paper's order, which stiff contact on a light body can drive unstable at 1 kHz.
  bool implicit_contact = true;
  // As a field body (role field): its deformed distance field (paper sec. 4.2). Scene key
  // deformable.field: {proxies: 40, neighbours: 5, domains: 1 | [{box: [...]}, {halfspace:
  // [nx, ny, nz, c]}, ...], overlap: metres, seed: 1, force_at: nearest | weighted}.
  DeformedFieldOptions field;
};

struct BodySpec {
  std::string name;
  std::string mesh;                  // file name (data search path) or "shape:params"
  std::string mesh_where;            // "FILE:LINE: bodies[i].mesh", for errors about the mesh
  // A mesh held in memory (Python's contactlab.Mesh, another tool's arrays): when set, the body
  // takes it instead of reading MESH, which then only names it; scale and center still apply.
  // Cached fields and pointshells are keyed by its content, as for a file.
  std::shared_ptr<const TriangleMesh> mesh_data;
  double scale = 1.0;
  bool center = false;
  Pose pose;                         // X_WBody at the scene's start
  // Two-body scene: "pointshell" or "field". Scene of many bodies (Scene::tool): what the body
  // may be in its pairs, "pointshell", "field" or "both" (the default there).
  std::string role;
  FieldSpec field;
  PointshellSpec pointshell;
  std::optional<DeformableSpec> deformable;  // none: rigid
  // Scene of many bodies: how far its surface may move from where its reduced model's rest shape
  // has it, metres, growing its broad-phase box (< 0: a tenth of its largest half-extent;
  // a rigid body's is 0).
  double deformation_bound = -1;
  ParamValues model_blocks;          // the registered models' blocks (pressure_field, inner_spheres, ...)
};


// A pair of a scene of many bodies (Scene::tool): two bodies the scene lets touch, and the
// model between them. By default the tool against every other body; the scene's `pairs:` adds
// pairs between other bodies and overrides a pair's model and its parameters.
struct PairSpec {
  std::array<int, 2> bodies{-1, -1};  // indices into Scene::bodies, as the pair names them
  std::string model;                  // a registered model; "" the model being compared; "none": no pair
  bool has_params = false;            // its own model section (below) instead of the scene's
  ContactParams params;
  ParamValues model_params;
  std::string where;                  // "FILE:LINE: pairs[i]" (or the scene's file for a default pair)
};

struct Scene {
  std::string name;
  std::string file;                  // where it was read from
  BodySpec pointshell_body;          // body A
  BodySpec field_body;               // body B
  ContactParams model;               // the "model:" section's keys every model shares
  ParamValues model_params;          // its keys of each registered model
  std::int64_t node_budget = 0;      // warm threshold V_W, nodes per cycle; 0 = unlimited
  std::vector<std::string> models;   // model names to compare (default: pointshell)
  // A scene of many bodies (`tool:` given, or more than two bodies): every body in file order,
  // the one the device or the trajectory moves, and the pairs (default ones included, "none"
  // ones left out); field_body holds the tool (the haptic body H) and pointshell_body another
  // body. A two-body
  // scene without `tool:` has tool -1 and no BODIES or PAIRS: pointshell_body and field_body
  // are its bodies.
  std::vector<BodySpec> bodies;
  int tool = -1;
  std::vector<PairSpec> pairs;
  std::vector<std::string> warnings;  // what the scene holds that nothing uses (a body in no pair)
  bool many_bodies() const { return tool >= 0; }
  // Every body: BODIES in a scene of many, else the two (pointshell_body, field_body).
  std::vector<const BodySpec*> AllBodies() const;
  // Throws Error("FILE: WHAT ...") when this is a scene of many bodies, for the commands that
  // read two bodies only.
  void RequireTwoBodies(std::string_view what) const;

  // The same scene with the roles of the two bodies exchanged.
  Scene Swapped() const;
};

// The parameter tables of a scene's blocks (util/param_table.h): parsing, range checks, cache
// keys (scene/scene_assets.cc), sweep aliases (experiment/experiment_config.cc) and the
// scene reference all come from them.
const ParamTable<BodySpec>& BodyParams();
const ParamTable<FieldSpec>& FieldParams();
const ParamTable<PointshellSpec>& PointshellParams();
const ParamTable<DeformableSpec>& DeformableParams();
const ParamTable<DeformedFieldOptions>& DeformedFieldParams();

// A block of a scene as sweeps and the reference see it: the key path a sweep alias stands for
// (PATH + key; "" for a block no alias reaches), the prefix of the alias names, the keys a
// sweep may name alone, and the block's section of the reference.
struct SceneBlock {
  std::string path;
  std::string alias_prefix;
  std::vector<std::string> sweep_keys;
  std::string reference;
  // The value of the block's KEY in a scene, as the reference shows it ("" for a block no path
  // reaches or an unknown key).
  std::function<std::string(const Scene&, const std::string& key)> value;
};
const std::vector<SceneBlock>& SceneBlocks();
// Every block's table, as Markdown (`contactlab params`, docs/scene-reference.md).
std::string SceneReference();

// A pair of a scene of many bodies as its model takes it: the model (the pair's own, else
// DEFAULT_MODEL) and the two bodies in its A/B order (indices into Scene::bodies): as the pair
// names them when each may take its role (BodySpec::role against the model's needs), else
// exchanged. Throws Error naming the pair when neither order fits, when the model is unknown or
// when it refuses a deformable body (CheckContactModel).
struct OrderedPair {
  std::string model;
  int A = -1;
  int B = -1;
};
OrderedPair OrderPair(const Scene& scene, const PairSpec& pair, std::string_view default_model);

// Reads a scene from a YAML node (a whole file, or the "scene" key of an experiment).
Scene ParseScene(const ConfigNode& node);
Scene LoadScene(const std::filesystem::path& file);
// SCENE with the keys that NODE, a model section ("model:" keys), gives replacing its own: the
// model parameters and node_budget, each value checked as in a scene file. What the Python
// module's Scene.model(name, k_C=...) applies. Throws Error naming NODE's file, line and key.
Scene WithModelSection(Scene scene, const ConfigNode& node);

// Reads a pose given as [x,y,z,qw,qx,qy,qz] or {position: [..], rotation: [qw,qx,qy,qz]}
// or {position: [..], rotation_vector: [..]} (radians). The quaternion must be unit length
// (NonUnitQuaternionError); throws Error naming NODE's file and line otherwise.
Pose ParsePoseNode(const ConfigNode& node);

}  // namespace contactlab
