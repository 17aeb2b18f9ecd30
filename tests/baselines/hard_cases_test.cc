// Hard cases for every registered contact model, each run as (A,B) and (B,A) (Scene::Swapped):
// deep penetration past the field body's medial axis, thin and sharp features, degenerate
// contact, motion extremes under temporal coherence and input extremes (issue 20). Each
// evaluation is checked against physical bounds, never against the code itself:
//
//  * force, torque and K_B finite;
//  * |F| <= k_C L D, where D is the largest depth one contact can report. Each contact pushes
//    with k |d| and the L/l rule keeps sum k <= k_C L (l < L contacts: k_C l; l >= L: k_C L),
//    so |F| <= k_C L max|d|. Field models (pointshell, pointshell-linear, vps, vps-repulsion,
//    reference) read depths from B: no point inside B lies farther than h_B = half the
//    smallest extent of B's bounding box from B's surface (the segment to the nearest box face
//    leaves B), trilinear interpolation never exceeds the grid values, and VPS's interior depth
//    is half a voxel diagonal: D = max(h_B, one voxel diagonal of B's field). Mesh-pair models
//    (fcl, bullet) report triangle-pair depths: D = the larger body's bounding-box diagonal
//    plus Bullet's two 0.5 mm margins;
//  * |torque| <= R k_C L D, R = farthest point of A's or B's world bounding box from B's origin
//    (every contact point lies in A's or B's extent or between them);
//  * K_B (halfspace rule, unit N and g per contact, sum k <= k_C L): |K_ff|_F <= k_C L,
//    |K_fτ|_F <= k_C L R, |K_τf|_F <= |F| + k_C L R, |K_ττ|_F <= k_C L R²;
//  * no force when the bodies are farther apart than the models' resolution (a voxel diagonal
//    of each field; Bullet's margins);
//  * where the push defines a direction (before either body's medial axis along the push), the
//    force on B points along B's push (cos >= 0.5), and there is a force once the bodies overlap
//    by a voxel of B's field;
//  * with temporal coherence, the same force as a model reset before every cycle (a full
//    traversal) — for motions within the scene's max_point_speed, and for a teleport when
//    the caller resets on a too-fast motion as the haptic cycle does (haptics/haptic_cycle.h);
//  * no allocation in Evaluate once a case's path has run once, for models that promise it
//    (pointshell, pointshell-linear, vps, vps-repulsion, fcl); bullet and reference document
//    that they allocate: recorded, not checked;
//  * a proxy model (ContactModel::Proxy: pointshell-ccd) is a spring between B and a proxy of B
//    held outside A, so the penalty bounds above do not apply to it. Instead: the force stays
//    within k_C L times how far B's relative pose has travelled along the path plus twice the
//    larger body's bounding-box diagonal (the proxy never wanders off); K_B is symmetric,
//    negative semidefinite and |K_ff|_F <= sqrt(3) k_C L (a projector scaled by the spring);
//    A's points at the proxy pose are never deeper in B's field than a voxel diagonal (the proxy
//    does not enter B); the force on B points along B's push at every depth, past the medial
//    axis too (where the case defines a direction at all), and there is no force before the
//    bodies first come within the apart distance.
//    Its state is its history, so it is not compared with a model reset every cycle;
//  * with a deformable body (the paper's model only; the others refuse it) at a random q every
//    cycle: the same checks, with A's points and B's surface moved by at most U |q| (U the
//    largest |U_i|_F of A's points or B's proxies), and the reduced forces and stiffnesses
//    finite and bounded, |f| <= U k_C L D and |K|_F <= U^2 k_C L.
//
// A failing check prints the model, the case, both poses with %.17g and the scene, so it
// replays with `contactlab contact SCENE.yaml --model M --pose-a ... --pose-b ...`. Failures
// that are known properties of a model (a baseline's failure is a finding) are listed in
// kFindings with the reason; they are printed, not failed. A model may refuse a case only as
// kRefusals lists (with the reason); any other refusal fails. The medial-axis summary line per
// model and order gives the peak force, the force at the deepest point and whether it inverts.
#include <fnmatch.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "allocation_counter.h"
#include "contact/register_contact_models.h"
#include "baselines/pressure_field/pressure_field_params.h"
#include "contact/model_registry.h"
#include "experiment/deformable_fixture.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "geometry/procedural_shapes.h"
#include "test_support.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kC = 1000;  // N/m
constexpr int kL = 10;
constexpr double kDt = 1e-3;  // s per cycle

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string PoseText(const Pose& X) {
  const auto& q = X.rotation;
  return Num(X.translation.x()) + "," + Num(X.translation.y()) + "," + Num(X.translation.z()) + "," + Num(q.w()) +
         "," + Num(q.x()) + "," + Num(q.y()) + "," + Num(q.z());
}

Pose Translation(double x, double y, double z) { return Pose::FromTranslation(Eigen::Vector3d(x, y, z)); }
Pose Rotated(const Eigen::Vector3d& w, const Eigen::Vector3d& t) { return {RotationFromVector(w), t}; }

// One body of a case: procedural mesh and its sampling.
struct BodyDef {
  std::string mesh;
  int field_resolution = 48;
  int points = 1024;
  int levels = 3;
  double scale = 1;
  double padding = 0.1;  // field padding, fraction of the largest extent
  bool center = false;   // move the bounding-box centre to the body origin
  // A small reduced deformable model (linear modal, 4 modes on an 8-cell tet mesh, free; as B
  // its deformed field of one domain), given a random q every cycle: see HardCase::deformation.
  bool deformable = false;
};

// One cycle of a case: poses of body 1 and body 2, and the geometric overlap along the push.
struct Step {
  Pose X_W1, X_W2;
  double depth = 0;  // metres of overlap of body 1 into body 2 along the push (< 0: apart)
};

struct HardCase {
  std::string name;
  BodyDef body1, body2;
  std::vector<Step> steps;
  Eigen::Vector3d push = Eigen::Vector3d::Zero();  // motion of body 1 against body 2 (world); 0: none
  // Direction checked while depth < this, per order (0: body 1 is A; 1: body 2 is A). Each
  // value is the depth at which the first point of A reaches a medial surface of B (or of A),
  // minus one voxel of B's field; 0 or less: no direction is defined.
  double direction_until[2] = {0, 0};
  bool coherence = false;
  double max_point_speed = 1.0;  // m/s declared in the scene
  bool compare_fresh = false;    // with coherence: equal to a model reset every cycle
  bool guard = false;            // reset the model when a step outruns max_point_speed
  bool bounds = true;            // the size bounds hold (not for non-unit quaternions)
  // Print the medial-axis summary line (peak force, force at the deepest point, inversion).
  bool medial_summary = false;
  // When set, the steps of each order are placed from the order's assets (a pointshell point
  // on a grid node of B's field, ...); STEPS then holds the scene's start poses only.
  std::function<std::vector<Step>(SceneAssets& assets, int order)> place;
  // Metres: each deformable body takes, every cycle, a random q (seeded by the cycle) moving a
  // vertex of its simulation mesh by up to this much.
  double deformation = 0;
  std::string model_keys;  // more keys of the scene's model section ("key: value, ...")
};

// The scene text of CASE with body 1 (ORDER 0) or body 2 (ORDER 1) as the pointshell body.
std::string SceneText(const HardCase& c, int order) {
  std::ostringstream s;
  auto body = [&](const char* name, const BodyDef& b, Pose X, const char* role) {
    // The scene's start pose must parse: a non-unit quaternion is written normalised (the
    // cycles pass the raw one).
    X.rotation = X.rotation.norm() > 1e-12 ? X.rotation.normalized() : Eigen::Quaterniond::Identity();
    s << "  - name: " << name << "\n    mesh: \"" << b.mesh << "\"\n    scale: " << Num(b.scale)
      << "\n    center: " << (b.center ? "true" : "false")
      << "\n    pose: [" << PoseText(X) << "]\n    role: " << role << "\n    pointshell: {points: " << b.points
      << ", levels: " << b.levels << "}\n    field: {resolution: " << b.field_resolution
      << ", padding: " << Num(b.padding) << "}\n";
    if (b.deformable) s << "    deformable: {model: linear, modes: 4, cells: 8}\n";
  };
  s << "name: hard-" << c.name << "\nbodies:\n";
  body("one", c.body1, c.steps.front().X_W1, order == 0 ? "pointshell" : "field");
  body("two", c.body2, c.steps.front().X_W2, order == 0 ? "field" : "pointshell");
  s << "model: {k_C: " << kC << ", L: " << kL << ", coherence: " << (c.coherence ? "true" : "false")
    << ", max_point_speed: " << Num(c.max_point_speed) << (c.model_keys.empty() ? "" : ", " + c.model_keys) << "}\n";
  return s.str();
}

// The registry's traits of model M (contact/model_registry.h): whether its contacts begin
// within a voxel of a field (else a mesh-pair library's margin), and whether its queries
// promise no allocation.
bool IsFieldModel(const std::string& m) { return !FindContactModel(m)->mesh_pair_contacts; }
bool PromisesNoAllocation(const std::string& m) { return !FindContactModel(m)->allocates; }
// The penalty laws' bounds (|F| <= k_C L D and the like) hold for models whose force is k_C
// times depths; the volumetric models follow laws of their own: pressure-field's force is at
// most its largest modulus times the contact area (checked instead), inner-spheres' is k_V
// times the sphere pairs' intersection discs.
bool PenaltyLaw(const std::string& m) { return m != "pressure-field" && m != "inner-spheres"; }
constexpr double kPressureModulus = PressureFieldSpec().modulus;  // every hard case's bodies

// Known properties of models that break a check (findings, not regressions). order: "AB",
// "BA" or "*"; case "*" matches every case.
struct Finding {
  const char* model;
  const char* hard_case;
  const char* order;
  const char* check;
  const char* reason;
};
const std::vector<Finding> kFindings = {
    // FINDINGS-BEGIN
    // Mesh-pair models see only intersecting triangles: a bar fully inside the block has none,
    // so the force vanishes and the tool sinks (from 3 voxels deep: the bar is 6 mm thick).
    {"fcl", "bar-into-block", "AB", "has-force", "no triangle pairs intersect once the bar is fully inside"},
    {"bullet", "bar-into-block", "AB", "has-force", "no triangle pairs intersect once the bar is fully inside"},
    // Temporal coherence trusts the scene's max_point_speed (paper sec. 3.4); a 4 cm jump in one
    // cycle wakes no sleeping node of the plate's pointshell and the new contact is missed.
    // The haptic cycle resets the model on such a jump (teleport-guarded passes).
    {"pointshell", "teleport-unguarded", "BA", "coherence", "coherence by contract; guarded by the haptic cycle"},
    {"pointshell", "teleport-unguarded", "BA", "has-force", "coherence by contract; guarded by the haptic cycle"},
    {"vps", "teleport-unguarded", "BA", "coherence", "distance-layer coherence by contract; guarded by the haptic cycle"},
    {"vps", "teleport-unguarded", "BA", "has-force", "distance-layer coherence by contract; guarded by the haptic cycle"},
    {"vps-repulsion", "teleport-unguarded", "BA", "coherence", "distance-layer coherence by contract; guarded by the haptic cycle"},
    {"vps-repulsion", "teleport-unguarded", "BA", "has-force", "distance-layer coherence by contract; guarded by the haptic cycle"},
    // Bullet's lengths are absolute (0.5 mm GImpact margins, subtracted twice; its contact
    // thresholds): at 1e-9 scale the margins swamp a 1e-12 m contact, at 1e3 they shift it.
    {"bullet", "scale-1e-9", "*", "direction", "absolute 0.5 mm margins against a 1e-12 m contact"},
    {"bullet", "scale-1e-9", "*", "scaling", "absolute 0.5 mm margins against a 1e-12 m contact"},
    {"bullet", "scale-1e3", "*", "scaling", "absolute lengths in Bullet's contact generation"},
    // The quadrature reference subdivides A's triangles to an absolute 0.5 mm edge: at 1e-9
    // scale each triangle is one centroid sample, too coarse for the sphere (B, A order).
    {"reference", "scale-1e-9", "*", "scaling", "absolute 0.5 mm quadrature edge: one sample per triangle"},
    // Pressure times area: at one modulus the force grows as the square of the scene's size
    // (Elandt et al.'s law; E is in Pa), where the penalty laws grow linearly.
    {"pressure-field", "scale-1e-9", "*", "scaling", "pressure x area: force scales as s^2 at a fixed modulus"},
    {"pressure-field", "scale-1e3", "*", "scaling", "pressure x area: force scales as s^2 at a fixed modulus"},
    // The inner-sphere packing places prototypes at float-rounded positions against float field
    // samples; both round differently at another scale, and a packing, greedy, follows each
    // choice: at 1e-9 the spheres settle elsewhere in the voids (9.5 %; 3.8 % at 1e3).
    {"inner-spheres", "scale-1e-9", "*", "scaling", "a greedy packing follows the scale's float rounding"},
    // A blade 0.4 mm thick on 1.5 mm cells: its field barely dips below zero, so its extent (and
    // pressure) is resolved only where a lattice vertex falls inside it.
    {"pressure-field", "blade-on-block", "AB", "has-force", "sub-voxel blade: no resolved inside to carry pressure"},
    // Greedy inner spheres stop short of a thin body's surface and of flat faces: a needle or a
    // bar's packing meets the other's in a few pairs whose line of centres is not the push, and
    // a corner one voxel deep meets no sphere at all.
    {"inner-spheres", "bar-into-block", "AB", "direction", "few sphere pairs, lines of centres off the push"},
    {"inner-spheres", "needle-into-plate", "AB", "direction", "few sphere pairs, lines of centres off the push"},
    {"inner-spheres", "corner-into-face", "BA", "has-force", "spheres stop short of the surface: one voxel unseen"},
    // FINDINGS-END
};

// The hard cases a model refuses to take (MakeSceneContactModel throws), each with the reason
// and a phrase of the refusal's message. Any other refusal fails the test, and so does a listed
// refusal that no longer happens. hard_case is a pattern (fnmatch); order "AB", "BA" or "*".
struct Refusal {
  const char* model;
  const char* hard_case;
  const char* order;
  const char* message_has;
  const char* reason;
};
const std::vector<Refusal> kRefusals = {
    // Only the paper's model renders a deformable body (paper sec. 4: deformable pointshell,
    // deformed field); every other model refuses a scene with one rather than treat it as rigid.
    {"bullet", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"fcl", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"inner-spheres", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"pointshell-ccd", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"pressure-field", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"reference", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"vps", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    {"vps-repulsion", "*-deformable-*", "*", "is deformable", "renders rigid bodies only"},
    // The 4 mm plate on an 8-cell field (7.5 mm cells) has no sample inside it: its field has no
    // zero crossing to sample a pointshell on (the plate as A), no inside for a pressure field
    // or a sphere packing (either order).
    {"pointshell", "fields-8", "BA", "no zero crossing", "no pointshell on a field without a surface"},
    {"pointshell-linear", "fields-8", "BA", "no zero crossing", "no pointshell on a field without a surface"},
    {"pointshell-ccd", "fields-8", "BA", "no zero crossing", "no pointshell on a field without a surface"},
    {"vps", "fields-8", "BA", "no zero crossing", "no pointshell on a field without a surface"},
    {"vps-repulsion", "fields-8", "BA", "no zero crossing", "no pointshell on a field without a surface"},
    {"pressure-field", "fields-8", "*", "has no inside", "no negative sample to carry a pressure"},
    {"inner-spheres", "fields-8", "*", "no grid point deeper than the smallest sphere", "no inside to pack spheres in"},
    // The quadrature reference's absolute 0.5 mm edge on metre-sized bodies: past its sample cap.
    {"reference", "scale-1e3", "*", "more than 50 million samples", "absolute 0.5 mm quadrature edge"},
};

const Refusal* FindRefusal(const std::string& model, const std::string& hard_case, int order) {
  for (const Refusal& r : kRefusals) {
    if (model != r.model || ::fnmatch(r.hard_case, hard_case.c_str(), 0) != 0) continue;
    if (std::string(r.order) != "*" && std::string(r.order) != (order == 0 ? "AB" : "BA")) continue;
    return &r;
  }
  return nullptr;
}

// MODEL made for HARD_CASE in ORDER, or null when it refuses the case as kRefusals expects (a
// refusal not listed, or a listed one that did not happen, fails the test).
std::unique_ptr<ContactModel> MakeOrExpectRefusal(const std::string& model, const std::string& hard_case, int order,
                                                  const Scene& scene, SceneAssets& assets) {
  const char* order_name = order == 0 ? "AB" : "BA";
  const Refusal* expected = FindRefusal(model, hard_case, order);
  try {
    std::unique_ptr<ContactModel> made = MakeSceneContactModel(model, scene, assets);
    EXPECT_EQ(expected, nullptr) << model << " took " << hard_case << " " << order_name
                                 << ", which kRefusals says it refuses (" << (expected ? expected->reason : "") << ")";
    return made;
  } catch (const Error& e) {
    if (expected == nullptr) {
      ADD_FAILURE() << model << " refused " << hard_case << " " << order_name
                    << ", not a refusal kRefusals expects: " << e.what();
    } else {
      EXPECT_NE(std::string(e.what()).find(expected->message_has), std::string::npos)
          << model << " refused " << hard_case << " " << order_name << " for another reason than "
          << expected->reason << ": " << e.what();
      std::printf("refused %s %s %s (expected: %s): %s\n", model.c_str(), hard_case.c_str(), order_name,
                  expected->reason, e.what());
    }
    return nullptr;
  }
}

const Finding* FindFinding(const std::string& model, const std::string& hard_case, int order,
                           const std::string& check) {
  for (const Finding& f : kFindings) {
    if (model != f.model || check != f.check) continue;
    if (std::string(f.hard_case) != "*" && hard_case != f.hard_case) continue;
    if (std::string(f.order) != "*" && std::string(f.order) != (order == 0 ? "AB" : "BA")) continue;
    return &f;
  }
  return nullptr;
}

Aabb WorldBox(const TriangleMesh& mesh, const Pose& X) {
  Aabb box;
  for (const auto& v : mesh.vertices) box.Extend(X * v);
  return box;
}

double FarthestCorner(const Aabb& box, const Eigen::Vector3d& p) {
  double r = 0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                            (i & 4) ? box.max.z() : box.min.z());
    r = std::max(r, (c - p).norm());
  }
  return r;
}

bool Finite(const ContactResult& r) {
  return r.on_B.force.allFinite() && r.on_B.torque.allFinite() && r.K_B.allFinite();
}

// Per-model summary of the whole run, printed at the end (the table of the report).
struct Tally {
  std::map<std::string, std::map<std::string, std::string>> cell;  // model -> case -> text
  // The force on B at a case's first step: (model, case, order) -> force, newtons.
  std::map<std::tuple<std::string, std::string, int>, Eigen::Vector3d> first_force;
};
Tally& Summary() {
  static Tally t;
  return t;
}

// Prints and clears the per-model table of the cases run so far (the test's report).
void PrintTable() {
  for (const auto& [model, cases] : Summary().cell) {
    std::printf("table %s:", model.c_str());
    for (const auto& [name, text] : cases) std::printf(" | %s %s", name.c_str(), text.c_str());
    std::printf("\n");
  }
  Summary().cell.clear();
}

class HardCaseRunner {
 public:
  explicit HardCaseRunner(const testing::TempDir& cache) {
    options_.cache_dir = cache.path();
    options_.verbose = false;
  }
  ~HardCaseRunner() { PrintTable(); }

  void Run(const HardCase& c) {
    for (int order = 0; order < 2; ++order) RunOrder(c, order);
  }

 private:
  // Reports one failed check: a known finding is printed, anything else fails the test with
  // what replays it.
  void Report(const std::string& model, const HardCase& c, int order, const std::string& check,
              const ContactQuery& q, const std::string& detail, std::set<std::string>* failed) {
    const std::string order_name = order == 0 ? "AB" : "BA";
    if (failed->count(check)) return;  // once per model, case, order and check
    failed->insert(check);
    if (const Finding* f = FindFinding(model, c.name, order, check)) {
      std::printf("FINDING %s %s %s %s: %s (%s)\n", model.c_str(), c.name.c_str(), order_name.c_str(), check.c_str(),
                  detail.c_str(), f->reason);
      return;
    }
    ADD_FAILURE() << model << " " << c.name << " " << order_name << ": " << check << ": " << detail
                  << "\nreplay: save the scene below as hard.yaml and run\n  contactlab contact hard.yaml --model "
                  << model << " --pose-a " << PoseText(q.X_WA) << " --pose-b " << PoseText(q.X_WB) << "\n"
                  << "  (cycle " << q.cycle << " of the case's path"
                  << (c.coherence ? "; with coherence the result depends on the cycles before it" : "") << ")\n"
                  << SceneText(c, order);
  }

  void RunOrder(const HardCase& c, int order) {
    const std::string order_name = order == 0 ? "AB" : "BA";
    const Scene base = ParseScene(ConfigNode::LoadString(SceneText(c, 0), "hard-" + c.name + ".yaml"));
    const Scene scene = order == 0 ? base : base.Swapped();
    SceneAssets assets(scene, options_);
    const std::vector<Step> steps = c.place ? c.place(assets, order) : c.steps;
    const TriangleMesh& mesh_A = *assets.A.mesh();
    const TriangleMesh& mesh_B = *assets.B.mesh();
    // B's field voxel (the field spans the box plus 10 % padding each side, RESOLUTION cells
    // along its longest side) and h_B, half B's smallest extent.
    const Aabb box_B0 = mesh_B.Bounds();
    const Eigen::Vector3d ext_B = box_B0.max - box_B0.min;
    const Aabb box_A0 = mesh_A.Bounds();
    const double voxel_B = ext_B.maxCoeff() * (1 + 2 * scene.field_body.field.padding) / scene.field_body.field.resolution;
    const double h_B = 0.5 * ext_B.minCoeff();
    const Eigen::Vector3d ext_A = box_A0.max - box_A0.min;
    const double voxel_A = ext_A.maxCoeff() * (1 + 2 * scene.pointshell_body.field.padding) / scene.pointshell_body.field.resolution;
    const double diag = std::max(ext_B.norm(), (box_A0.max - box_A0.min).norm());
    // The direction the force on B must take: body 1 moves along c.push into body 2, so
    // body 2 is pushed along it and body 1 against it.
    const Eigen::Vector3d push_on_B = order == 0 ? Eigen::Vector3d(c.push) : Eigen::Vector3d(-c.push);
    // Deformable bodies: each step's q, and U_A (U_B), the largest |U_i|_F over A's points (B's
    // proxies). A point moves by at most U_A |q_A|, a proxy by U_B |q_B|; a point force F acts
    // on a reduced force through U^T (a weighted mean of them), so |f| <= U sum |F_i|, and the
    // halfspace stiffness k sum w w^T has |K|_F <= U^2 sum k.
    const bool defo_A = scene.pointshell_body.deformable.has_value();
    const bool defo_B = scene.field_body.deformable.has_value();
    double U_A = 0, U_B = 0;
    if (defo_A) {
      const auto dps = assets.A.deformable_pointshell();
      for (int i = 0; i < dps->points().size(); ++i) U_A = std::max(U_A, dps->points().Basis(i).norm());
    }
    if (defo_B) {
      const auto field = assets.B.deformed_field();
      for (int i = 0; i < field->num_slots(); ++i) U_B = std::max(U_B, field->proxies().Basis(i).norm());
    }
    std::vector<ReducedState> q_A(steps.size()), q_B(steps.size());
    for (std::size_t i = 0; i < steps.size(); ++i) {
      std::mt19937 rng(unsigned(i) + 1);
      if (defo_A) q_A[i] = testing::RandomState(*assets.A.reduced_model(), c.deformation, &rng);
      if (defo_B) q_B[i] = testing::RandomState(*assets.B.reduced_model(), c.deformation, &rng);
    }
    ReducedVector f_A, f_B;  // fixed-capacity: no allocation in the cycle
    ReducedMatrix K_A, K_B;

    for (const std::string& name : ContactModelNames()) {
#if defined(__SANITIZE_ADDRESS__)
      // Milliseconds a query in Release, ten times that here: its own tests (PressureField.*)
      // run under the sanitizers; the Release suite runs it through every hard case.
      if (name == "pressure-field") continue;
#endif
      if (name == "reference" && steps.size() > 12) {
        std::printf("skip %s %s %s: offline reference (ms-s per query) on a %zu-cycle path\n", name.c_str(),
                    c.name.c_str(), order_name.c_str(), steps.size());
        Summary().cell[name][c.name] += order_name + ":skip ";
        continue;
      }
      std::unique_ptr<ContactModel> model = MakeOrExpectRefusal(name, c.name, order, scene, assets), fresh;
      if (!model) {
        Summary().cell[name][c.name] += order_name + ":refused ";
        continue;
      }
      if (c.compare_fresh) fresh = MakeSceneContactModel(name, scene, assets);
      const double D = IsFieldModel(name) ? std::max(h_B, std::sqrt(3.0) * voxel_B) : diag + 1e-3;
      // Bodies farther apart than this touch in no model: a voxel diagonal of each field (a
      // pointshell point, a voxel centre and a trilinear lookup each stay within one), or
      // Bullet's two 0.5 mm margins for the mesh-pair models.
      const double apart = IsFieldModel(name) ? std::sqrt(3.0) * (voxel_A + voxel_B) : 1e-3;
      std::set<std::string> failed;
      double peak = 0, peak_depth = 0, last_along = 0, last_depth = 0, min_along_after_peak = 1e300;
      // For a proxy model: how far B's pose relative to A has travelled from any earlier step
      // (translation plus rotation times R), and whether the bodies have come near yet.
      double travelled = 0;
      bool approached = false;  // the bodies came within the apart distance
      long allocations = 0;
      // A model that promises no allocation runs the path twice more, counting allocations only:
      // as in pass 0, then keeping its contacts (ContactModel::KeepContacts), which must not
      // make Evaluate allocate either.
      const int passes = PromisesNoAllocation(name) ? 3 : 1;
      for (int pass = 0; pass < passes; ++pass) {
        if (pass == 2) model->KeepContacts(1 << 12);
        model->Reset();
        for (std::size_t i = 0; i < steps.size(); ++i) {
          const Step& s = steps[i];
          ContactQuery q;
          q.X_WA = order == 0 ? s.X_W1 : s.X_W2;
          q.X_WB = order == 0 ? s.X_W2 : s.X_W1;
          q.cycle = std::int64_t(i);
          const BodyDeformation d_A{&q_A[i], &f_A, &K_A}, d_B{&q_B[i], &f_B, &K_B};
          if (defo_A) q.deformation_A = &d_A;
          if (defo_B) q.deformation_B = &d_B;
          // How far the deformations may have moved A's points and B's surface (metres).
          const double deformed_by = (defo_A ? U_A * q_A[i].q.norm() : 0.0) + (defo_B ? U_B * q_B[i].q.norm() : 0.0);
          // The haptic cycle's guard: a step faster than max_point_speed resets the model.
          if (c.guard && i > 0) {
            const Step& p = steps[i - 1];
            const double moved = ((s.X_W1.translation - s.X_W2.translation) - (p.X_W1.translation - p.X_W2.translation)).norm();
            if (moved > c.max_point_speed * kDt) model->Reset();
          }
          const long before = testing::AllocationCount();
          const ContactResult r = model->Evaluate(q);
          const long used = testing::AllocationCount() - before;
          if ((pass >= 1 || (passes == 1 && i > 0))) allocations += used;
          if (pass >= 1) continue;  // the later passes only count allocations

          const double F = r.on_B.force.norm();
          Pose X_WP;
          const bool proxy = model->Proxy(&X_WP);
          if (proxy) {
            const Pose X_AB = q.X_WA.Inverse() * q.X_WB;
            for (std::size_t j = 0; j < i; ++j) {
              const Step& e = steps[j];
              const Pose X_AB_j = (order == 0 ? e.X_W1 : e.X_W2).Inverse() * (order == 0 ? e.X_W2 : e.X_W1);
              const double angle = Eigen::AngleAxisd((X_AB.rotation * X_AB_j.rotation.conjugate()).normalized()).angle();
              travelled = std::max(travelled, (X_AB.translation - X_AB_j.translation).norm() + angle * diag);
            }
          }
          if (i == 0) Summary().first_force[{name, c.name, order}] = r.on_B.force;
          if (!Finite(r) || (defo_A && !(f_A.allFinite() && K_A.allFinite())) ||
              (defo_B && !(f_B.allFinite() && K_B.allFinite()))) {
            Report(name, c, order, "finite", q, "non-finite force, torque, K_B or reduced force or stiffness", &failed);
            continue;
          }
          if (c.bounds && proxy) {
            const double kmax = kC * kL * (1 + 1e-6);
            if (F > kmax * (travelled + 2 * diag)) {
              Report(name, c, order, "proxy-force-bound", q,
                     "|F| " + Num(F) + " N > k_C L (travelled + 2 diag) = " + Num(kC * kL * (travelled + 2 * diag)), &failed);
            }
            const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (r.K_B + r.K_B.transpose()));
            if ((r.K_B - r.K_B.transpose()).norm() > 1e-9 * (1 + r.K_B.norm()) ||
                eig.eigenvalues().maxCoeff() > 1e-9 * (1 + r.K_B.norm()) ||
                r.K_B.block<3, 3>(0, 0).norm() > std::sqrt(3.0) * kmax) {
              Report(name, c, order, "proxy-stiffness", q,
                     "K_B not symmetric negative semidefinite with |K_ff| <= sqrt(3) k_C L (largest eigenvalue " +
                         Num(eig.eigenvalues().maxCoeff()) + ", |K_ff| " + Num(r.K_B.block<3, 3>(0, 0).norm()) + ")",
                     &failed);
            }
            // A's points at the proxy pose stay outside B (within a voxel diagonal).
            const Pointshell& shell = *assets.A.pointshell();
            const Pose X_BA = X_WP.Inverse() * q.X_WA;
            double deepest = 0;
            for (int k = 0; k < shell.num_points(); ++k) {
              deepest = std::min(deepest, assets.B.field()->Distance(X_BA * Eigen::Vector3d(shell.x[k], shell.y[k], shell.z[k])));
            }
            // (A path that starts with the bodies overlapping starts the proxy inside.)
            if (steps.front().depth < 0 && deepest < -std::sqrt(3.0) * voxel_B) {
              Report(name, c, order, "proxy-inside", q, "a point of A at the proxy is " + Num(-deepest) + " m inside B", &failed);
            }
          } else if (c.bounds) {
            const Aabb box_A = WorldBox(mesh_A, q.X_WA), box_B = WorldBox(mesh_B, q.X_WB);
            // A's deformed points lie within DEFORMED_BY of its rest box.
            const double R = std::max(FarthestCorner(box_A, q.X_WB.translation), FarthestCorner(box_B, q.X_WB.translation)) +
                             deformed_by;
            const double kmax = kC * kL * (1 + 1e-6);
            for (const auto& [deforms, U, f, K, body] :
                 {std::tuple{defo_A, U_A, &f_A, &K_A, "A"}, std::tuple{defo_B, U_B, &f_B, &K_B, "B"}}) {
              if (!deforms) continue;
              if (f->norm() > U * kmax * D || K->norm() > U * U * kmax) {
                Report(name, c, order, "reduced-bound", q,
                       std::string("body ") + body + ": |f| " + Num(f->norm()) + ", |K| " + Num(K->norm()) +
                           " over U k_C L D = " + Num(U * kC * kL * D) + ", U^2 k_C L = " + Num(U * U * kC * kL),
                       &failed);
              }
            }
            if (name == "pressure-field" && F > kPressureModulus * r.stats.contact_area * (1 + 1e-9)) {
              Report(name, c, order, "force-bound", q,
                     "|F| " + Num(F) + " N > E area = " + Num(kPressureModulus * r.stats.contact_area), &failed);
            }
            if (PenaltyLaw(name) && F > kmax * D) {
              Report(name, c, order, "force-bound", q, "|F| " + Num(F) + " N > k_C L D = " + Num(kC * kL * D), &failed);
            }
            if (PenaltyLaw(name) && r.on_B.torque.norm() > kmax * D * R) {
              Report(name, c, order, "torque-bound", q,
                     "|tau| " + Num(r.on_B.torque.norm()) + " > R k_C L D = " + Num(kC * kL * D * R), &failed);
            }
            const double kff = r.K_B.block<3, 3>(0, 0).norm(), kft = r.K_B.block<3, 3>(0, 3).norm();
            const double ktf = r.K_B.block<3, 3>(3, 0).norm(), ktt = r.K_B.block<3, 3>(3, 3).norm();
            if (PenaltyLaw(name) && (kff > kmax || kft > kmax * R || ktf > F + kmax * R || ktt > kmax * R * R)) {
              Report(name, c, order, "stiffness-bound", q,
                     "|K| blocks " + Num(kff) + ", " + Num(kft) + ", " + Num(ktf) + ", " + Num(ktt) +
                         " over k_C L = " + Num(kC * kL) + " with R = " + Num(R),
                     &failed);
            }
          }
          if (s.depth >= -apart) approached = true;
          if (s.depth < -apart - deformed_by && F > 0 && !(proxy && approached)) {
            Report(name, c, order, "apart", q, "|F| " + Num(F) + " N with the bodies " + Num(-s.depth) + " m apart", &failed);
          }
          // Direction: before the medial axis the force on B points along B's push.
          const double along = push_on_B.norm() > 0 ? r.on_B.force.dot(push_on_B.normalized()) : 0;
          // (With deformable bodies not where the deformation alone may make the contact.)
          if (push_on_B.norm() > 0 && (s.depth < c.direction_until[order] - deformed_by || (proxy && c.direction_until[order] > 0)) &&
              (deformed_by == 0 || s.depth > deformed_by)) {
            if (F > 1e-9 && along < 0.5 * F) {
              Report(name, c, order, "direction", q,
                     "force on B " + Num(r.on_B.force.x()) + "," + Num(r.on_B.force.y()) + "," + Num(r.on_B.force.z()) +
                         " at depth " + Num(s.depth) + " is not along the push",
                     &failed);
            }
            if (s.depth >= voxel_B + deformed_by && F == 0) {
              Report(name, c, order, "has-force", q, "no force at depth " + Num(s.depth) + " m (" + Num(s.depth / voxel_B) + " voxels of B)", &failed);
            }
          }
          if (along > peak) {
            peak = along;
            peak_depth = s.depth;
            min_along_after_peak = along;
          }
          min_along_after_peak = std::min(min_along_after_peak, along);
          last_along = along;
          last_depth = s.depth;
          // Coherence: the same force as a full traversal.
          if (fresh && !proxy) {
            fresh->Reset();
            const ContactResult f = fresh->Evaluate(q);
            const double err = (r.on_B.force - f.on_B.force).norm();
            if (err > 1e-4 * f.on_B.force.norm() + 1e-9) {
              Report(name, c, order, "coherence", q,
                     "|F - F_full| " + Num(err) + " N, |F_full| " + Num(f.on_B.force.norm()) + " N at cycle " + std::to_string(i),
                     &failed);
            }
          }
        }
      }
      if (PromisesNoAllocation(name) && allocations > 0) {
        ContactQuery q;
        q.X_WA = order == 0 ? steps.back().X_W1 : steps.back().X_W2;
        q.X_WB = order == 0 ? steps.back().X_W2 : steps.back().X_W1;
        Report(name, c, order, "allocation", q,
               std::to_string(allocations) + " allocations in the later passes (contacts kept in the third)", &failed);
      } else if (allocations > 0) {
        std::printf("record %s %s %s: %ld allocations in Evaluate after the first call (documented)\n", name.c_str(),
                    c.name.c_str(), order_name.c_str(), allocations);
      }
      if (c.medial_summary) {
        std::printf("medial %s %s %s: peak along push %.4g N at depth %.4g m; min after peak %.4g N; at depth %.4g m: %.4g N%s\n",
                    c.name.c_str(), name.c_str(), order_name.c_str(), peak, peak_depth, min_along_after_peak, last_depth,
                    last_along, min_along_after_peak < -1e-9 ? " (inverts)" : "");
      }
      std::string text = order_name + ":";
      if (failed.empty()) {
        text += "pass";
      } else {
        for (const std::string& f : failed) text += (FindFinding(name, c.name, order, f) ? "finding-" : "FAIL-") + f + ",";
      }
      Summary().cell[name][c.name] += text + " ";
    }
  }

  AssetOptions options_;
};

// --- The cases -----------------------------------------------------------------------------

// Ball (r 1 cm) pushed down through a 4 mm plate and out the other side: 0.5 mm per cycle.
HardCase BallThroughPlate(int plate_resolution = 96, int ball_resolution = 48, const std::string& name = "ball-through-plate") {
  HardCase c;
  c.name = name;
  c.body1 = {"sphere:0.01,3", ball_resolution, 1024, 3};
  c.body2 = {"box:0.03,0.03,0.002,4", plate_resolution, 2048, 3};
  for (double z = 0.013; z >= -0.0130001; z -= 0.0005) c.steps.push_back({Translation(0.0007, -0.0003, z), Pose::Identity(), 0.012 - z});
  c.push = Eigen::Vector3d(0, 0, -1);
  // The ball's lowest point reaches the plate's mid-plane at depth 2 mm (the plate is B); the
  // plate's top face reaches the ball's centre at depth 1 cm (the ball is B); less a voxel.
  // An 8-cell field with the default 10 % padding has a conservative boundary minimum of 0
  // (sdf/signed_distance_grid.cc: sqrt(m² - h²/2) with m = 0.1 extent < h/√2), so no offset
  // level set closes inside it and pointshells refuse it; coarse fields get 50 % padding.
  const double padding = plate_resolution < 16 ? 0.5 : 0.1;
  c.body1.padding = c.body2.padding = padding;
  const double v_plate = 0.06 * (1 + 2 * padding) / plate_resolution, v_ball = 0.02 * (1 + 2 * padding) / ball_resolution;
  c.direction_until[0] = 0.002 - v_plate;
  c.direction_until[1] = 0.002 - v_ball;  // and the plate's own mid-plane at 2 mm
  c.medial_summary = true;
  return c;
}

// A 4 x 0.6 x 0.6 cm bar pushed into an 8 x 8 x 6 cm block until fully inside (its top 9 mm
// below the block's top face).
HardCase BarIntoBlock() {
  HardCase c;
  c.name = "bar-into-block";
  c.body1 = {"box:0.02,0.003,0.003,3", 48, 1024, 3};
  c.body2 = {"box:0.04,0.04,0.03,3", 48, 2048, 3};
  for (double z = 0.034; z >= 0.0179999; z -= 0.0005) c.steps.push_back({Translation(0.0011, 0.0007, z), Pose::Identity(), 0.033 - z});
  c.push = Eigen::Vector3d(0, 0, -1);
  // Bar points stay nearer the block's top (<= 1.8 cm) than its sides (>= 2 cm) or its
  // mid-plane (3 cm): direction defined throughout. Swapped: the block's top face reaches the
  // bar's mid-plane at 3 mm.
  c.direction_until[0] = 1;
  c.direction_until[1] = 0.003 - 0.04 * 1.2 / 48;
  return c;
}

// A blade 0.4 mm thick (sub-voxel: its 32-cell field has 1.5 mm voxels) pressed edge-down into
// a block, and lifted.
HardCase BladeOnBlock() {
  HardCase c;
  c.name = "blade-on-block";
  c.body1 = {"box:0.02,0.0002,0.01,2", 32, 1024, 3};
  c.body2 = {"box:0.03,0.03,0.01,3", 48, 2048, 3};
  for (double d : {-0.0005, 0.001, 0.003, 0.006}) c.steps.push_back({Translation(0.0003, 0.0002, 0.02 - d), Pose::Identity(), d});
  c.push = Eigen::Vector3d(0, 0, -1);
  c.direction_until[0] = 0.01 - 0.06 * 1.2 / 48;  // the block's mid-plane at 1 cm
  c.direction_until[1] = 0;  // the blade's medial surface is 0.2 mm from its faces: undefined
  return c;
}

// A needle (capsule r 0.4 mm, sub-voxel in its 48-cell field) tip-first into a 4 mm plate.
HardCase NeedleIntoPlate() {
  HardCase c;
  c.name = "needle-into-plate";
  c.body1 = {"capsule:0.0004,0.015", 48, 1024, 3};
  c.body2 = {"box:0.03,0.03,0.002,4", 96, 2048, 3};
  for (double d : {-0.0005, 0.0003, 0.001, 0.003, 0.006})
    c.steps.push_back({Translation(0.0002, 0.0001, 0.002 + 0.0154 - d), Pose::Identity(), d});
  c.push = Eigen::Vector3d(0, 0, -1);
  c.direction_until[0] = 0.002 - 0.06 * 1.2 / 96;
  c.direction_until[1] = 0;  // the needle's axis is 0.4 mm inside: undefined
  return c;
}

// Two 4 x 0.8 x 0.8 cm bars, edges crossed: body 1 along x with an edge down, body 2 along y
// with an edge up.
HardCase CrossedEdges() {
  HardCase c;
  c.name = "crossed-edges";
  c.body1 = {"box:0.02,0.004,0.004,3", 48, 1024, 3};
  c.body2 = {"box:0.004,0.02,0.004,3", 48, 1024, 3};
  const double e = 0.004 * std::sqrt(2.0);  // edge height above the centre
  const Pose X2 = Rotated(Eigen::Vector3d(0, M_PI / 4, 0), Eigen::Vector3d::Zero());
  for (double d : {-0.0003, 0.0005, 0.002}) {
    c.steps.push_back({Rotated(Eigen::Vector3d(M_PI / 4, 0, 0), Eigen::Vector3d(0.0004, -0.0003, 2 * e - d)), X2, d});
  }
  c.push = Eigen::Vector3d(0, 0, -1);
  // Each bar's centre line is 5.7 mm behind its edge.
  c.direction_until[0] = c.direction_until[1] = e - 0.04 * 1.2 / 48;
  return c;
}

// A thin-walled tube (outer r 6 mm, wall 0.5 mm, 3 cm long; the wall is about one voxel of
// its 96-cell field) lowered over a peg (capsule r 4 mm) with 1.5 mm clearance all round —
// the bodies stay apart — then pushed sideways until its wall presses into the peg and, at
// the last step, through it (0.8 mm > the wall).
HardCase TubeOverPeg() {
  HardCase c;
  c.name = "tube-over-peg";
  c.body1 = {"tube:0.006,0.0055,0.015", 96, 2048, 3};
  c.body2 = {"capsule:0.004,0.015", 96, 1024, 3};
  const double clearance = 0.0015;
  for (double z = 0.036; z >= 0.0099; z -= 0.0065) c.steps.push_back({Translation(0, 0, z), Pose::Identity(), -clearance});
  for (double d : {-0.0003, 0.0001, 0.0002, 0.0004, 0.0008}) {
    c.steps.push_back({Translation(clearance + d, 0.0002, 0.01), Pose::Identity(), d});
  }
  c.push = Eigen::Vector3d(1, 0, 0);
  // Tube as the pointshell: the peg's axis is 4 mm in, less a voxel of its field (3.8 cm at
  // 96 cells with 10 % padding). Peg as the pointshell: the wall's mid-surface is 0.25 mm
  // inside, less than a voxel of the tube's field (0.375 mm): checked anyway up to it, a
  // failure there is the sub-voxel wall's finding.
  c.direction_until[0] = 0.004 - 0.038 * 1.2 / 96;
  c.direction_until[1] = 0.00025;
  c.medial_summary = true;
  return c;
}

// A 2 cm cube, corner first, into a block face.
HardCase CornerIntoFace() {
  HardCase c;
  c.name = "corner-into-face";
  c.body1 = {"box:0.01,0.01,0.01,3", 48, 1024, 3};
  c.body2 = {"box:0.03,0.03,0.01,3", 48, 2048, 3};
  // Rotate the diagonal (1,1,1) onto -z... by the rotation taking (-1,-1,-1)/sqrt3 to -z.
  const Eigen::Quaterniond R = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(-1, -1, -1).normalized(), Eigen::Vector3d(0, 0, -1));
  const double corner = 0.01 * std::sqrt(3.0);
  for (double d : {-0.0003, 0.0005, 0.002, 0.006}) {
    c.steps.push_back({Pose{R, Eigen::Vector3d(0.0002, 0.0001, 0.01 + corner - d)}, Pose::Identity(), d});
  }
  c.push = Eigen::Vector3d(0, 0, -1);
  c.direction_until[0] = 0.01 - 0.06 * 1.2 / 48;
  c.direction_until[1] = corner - 0.02 * 1.2 / 48;  // the face reaches the cube's centre
  return c;
}

// The fandisk (CAD part, sharp creases; 3 x 3.1 x 1.6 cm), tilted, its lowest vertex pressed
// 0.5 and 1.5 mm into a plate.
HardCase FandiskOnPlate() {
  HardCase c;
  c.name = "fandisk-creases-on-plate";
  c.body1 = {"fandisk.obj", 48, 2048, 3, 0.006};
  c.body1.center = true;
  c.body2 = {"box:0.04,0.04,0.005,3", 48, 2048, 3};
  c.steps = {{Translation(0, 0, 0.03), Pose::Identity(), 0}};
  c.place = [](SceneAssets& assets, int order) {
    const TriangleMesh& mesh = order == 0 ? *assets.A.mesh() : *assets.B.mesh();
    const Eigen::Quaterniond R = RotationFromVector(Eigen::Vector3d(0.3, 0.2, 0.1));
    double lowest = 1e9;
    for (const auto& v : mesh.vertices) lowest = std::min(lowest, (R * v).z());
    std::vector<Step> steps;
    for (double d : {-0.0003, 0.0005, 0.0015}) steps.push_back({Pose{R, Eigen::Vector3d(0.001, -0.002, 0.005 - lowest - d)}, Pose::Identity(), d});
    return steps;
  };
  c.push = Eigen::Vector3d(0, 0, -1);
  c.direction_until[0] = 0.005 - 0.08 * 1.2 / 48;  // the plate's mid-plane, less a voxel
  c.direction_until[1] = 0.002;  // the part is 1.6 cm thick under its lowest vertex's region
  return c;
}

// Identical bodies at identical (skew) poses: no direction; finite and bounded.
HardCase Identical(const std::string& mesh, const std::string& name) {
  HardCase c;
  c.name = name;
  c.body1 = c.body2 = {mesh, 32, 1024, 3};
  const Pose X = Rotated(Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d(0.01 / 3, 0, -0.01 / 7));
  c.steps = {{X, X, 0}};
  return c;
}

// Flush face on face at exactly zero depth.
HardCase Flush() {
  HardCase c;
  c.name = "flush-faces";
  c.body1 = {"box:0.01,0.01,0.005,2", 32, 1024, 3};
  c.body2 = {"box:0.03,0.03,0.005,3", 48, 2048, 3};
  c.steps = {{Translation(0.001, -0.002, 0.01), Pose::Identity(), 0}};
  return c;
}

// Ball on a wide plate for the motion cases.
HardCase BallOnWidePlate(const std::string& name) {
  HardCase c;
  c.name = name;
  c.body1 = {"sphere:0.01,3", 32, 1024, 3};
  c.body2 = {"box:0.05,0.05,0.005,4", 64, 2048, 3};
  c.coherence = true;
  c.compare_fresh = true;
  c.push = Eigen::Vector3d(0, 0, -1);
  return c;
}

// Teleport: 10 cycles 1 mm deep at x = -2 cm, then 4 cm away in one cycle, 1.5 mm deep; the
// scene promises 1 m/s. GUARD: the caller resets the model on the jump as the haptic cycle does.
HardCase Teleport(bool guard) {
  HardCase c = BallOnWidePlate(guard ? "teleport-guarded" : "teleport-unguarded");
  c.guard = guard;
  const double top = 0.005 + 0.01;
  for (int i = 0; i < 10; ++i) c.steps.push_back({Translation(-0.02, 0.001, top - 0.001), Pose::Identity(), 0.001});
  for (int i = 0; i < 10; ++i) c.steps.push_back({Translation(0.02, 0.001, top - 0.0015), Pose::Identity(), 0.0015});
  c.direction_until[0] = c.direction_until[1] = 0.002;
  return c;
}

// 10 m/s (1 cm per cycle) back and forth across the plate 1 mm deep; the scene declares 12 m/s.
HardCase HighSpeed() {
  HardCase c = BallOnWidePlate("high-speed");
  c.max_point_speed = 12;
  const double top = 0.005 + 0.01;
  for (int i = 0; i < 40; ++i) {
    const int k = i % 8;  // -0.04 .. 0.03 and back
    const double x = -0.035 + 0.01 * (k < 4 ? k : 8 - k);
    c.steps.push_back({Translation(x, 0.0005, top - 0.001), Pose::Identity(), 0.001});
  }
  c.direction_until[0] = c.direction_until[1] = 0.002;
  return c;
}

// Creep: 1 µm per cycle from 0.2 mm apart to 0.8 mm deep.
HardCase Creep() {
  HardCase c = BallOnWidePlate("creep");
  const double top = 0.005 + 0.01;
  for (int i = 0; i <= 1000; ++i) {
    const double d = -0.0002 + 1e-6 * i;
    c.steps.push_back({Translation(0.0013, -0.0007, top - d), Pose::Identity(), d});
  }
  c.direction_until[0] = c.direction_until[1] = 0.002;
  return c;
}

// Ball 1 mm into a plate with body 1's quaternion scaled by SCALE (not unit; the Pose contract
// says unit and every pose read from a file or argument is refused otherwise, but a device or a
// caller of the library may not keep it).
HardCase Quaternion(double scale, const std::string& name) {
  HardCase c;
  c.name = name;
  c.body1 = {"sphere:0.01,3", 32, 1024, 3};
  c.body2 = {"box:0.03,0.03,0.005,3", 48, 2048, 3};
  Pose X1 = Rotated(Eigen::Vector3d(0.2, 0.1, -0.3), Eigen::Vector3d(0.001, 0, 0.015 - 0.001));
  X1.rotation.coeffs() *= scale;
  c.steps = {{X1, Pose::Identity(), 0.001}};
  c.bounds = false;  // a scaled quaternion's matrix stretches the body: only finiteness
  return c;
}

// The ball-on-plate contact of Quaternion at unit quaternion, both bodies scaled by SCALE
// (the pose and depth too): a similar geometry.
HardCase Scaled(double scale, const std::string& name) {
  HardCase c;
  c.name = name;
  c.body1 = {"sphere:0.01,3", 32, 1024, 3, scale};
  c.body2 = {"box:0.03,0.03,0.005,3", 48, 2048, 3, scale};
  c.steps = {{Rotated(Eigen::Vector3d(0.2, 0.1, -0.3), scale * Eigen::Vector3d(0.001, 0, 0.015 - 0.001)), Pose::Identity(),
              0.001 * scale}};
  c.push = Eigen::Vector3d(0, 0, -1);
  c.direction_until[0] = c.direction_until[1] = 0.003 * scale;
  return c;
}

// A pointshell point of A placed exactly at a spot of B's field: WHERE(field) gives the spot in
// B's frame. A small sphere (body 1, r 6 mm) against a sphere (body 2, r 1 cm), both orders;
// the point used is A's point whose inward normal points most along -z (A's top), so A hangs
// below the spot and overlaps B.
HardCase PointAt(const std::string& name, std::function<Eigen::Vector3d(const DistanceField&)> where) {
  HardCase c;
  c.name = name;
  c.body1 = {"sphere:0.006,2", 24, 512, 3};
  c.body2 = {"sphere:0.01,3", 32, 1024, 3};
  c.steps = {{Translation(0, 0, 0.012), Pose::Identity(), 0}};
  c.place = [where](SceneAssets& assets, int order) {
    const Pointshell& shell = *assets.A.pointshell();
    int top = 0;
    for (int i = 0; i < shell.num_points(); ++i) {
      if (shell.nz[i] < shell.nz[top]) top = i;
    }
    const Eigen::Vector3d p_A(shell.x[top], shell.y[top], shell.z[top]);
    const Eigen::Vector3d p_B = where(*assets.B.field());
    const Pose X_WB = Rotated(Eigen::Vector3d(0, 0, 0.4), Eigen::Vector3d(0.01 / 3, -0.01 / 7, 0.002));
    const Eigen::Quaterniond R_WA = RotationFromVector(Eigen::Vector3d(0, 0, -0.2));
    const Pose X_WA{R_WA, X_WB * p_B - R_WA * p_A};
    return std::vector<Step>{order == 0 ? Step{X_WA, X_WB, 0} : Step{X_WB, X_WA, 0}};
  };
  return c;
}

// The grid node of FIELD nearest to 70 % of the way from B's centre to its top.
Eigen::Vector3d GridNodeNearTop(const DistanceField& field) {
  const Aabb box = field.box();
  const Eigen::Vector3d target(0.5 * (box.min.x() + box.max.x()), 0.5 * (box.min.y() + box.max.y()),
                               0.7 * (0.5 * (box.max.z() - box.min.z()) / 1.2));
  const Eigen::Vector3d ijk = ((target - field.origin()) / field.spacing()).array().round();
  return field.GridPoint(int(ijk.x()), int(ijk.y()), int(ijk.z()));
}

// A point exactly on the top face of FIELD's box, off its centre.
Eigen::Vector3d BoxTop(const DistanceField& field) {
  const Aabb box = field.box();
  return Eigen::Vector3d(0.3 * box.min.x() + 0.7 * box.max.x(), 0.5 * (box.min.y() + box.max.y()), box.max.z());
}

// B's centre, on the medial axis of a sphere (the distance gradient is undefined there).
Eigen::Vector3d Centre(const DistanceField& field) {
  const Aabb box = field.box();
  return 0.5 * (box.min + box.max);
}

TEST(HardCases, DeepPenetrationPastTheMedialAxis) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  runner.Run(BallThroughPlate());
  runner.Run(BarIntoBlock());
}

TEST(HardCases, ThinAndSharpFeatures) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  runner.Run(BladeOnBlock());
  runner.Run(NeedleIntoPlate());
  runner.Run(TubeOverPeg());
  runner.Run(CrossedEdges());
  runner.Run(CornerIntoFace());
  runner.Run(FandiskOnPlate());
}

TEST(HardCases, DegenerateContact) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  runner.Run(Identical("sphere:0.01,3", "identical-spheres"));
  runner.Run(Identical("box:0.01,0.007,0.005,2", "identical-boxes"));
  runner.Run(Flush());
  runner.Run(PointAt("point-on-grid-node", GridNodeNearTop));
  runner.Run(PointAt("point-on-field-box-boundary", BoxTop));
  runner.Run(PointAt("point-on-medial-axis", Centre));
}

TEST(HardCases, MotionExtremesWithCoherence) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  runner.Run(Teleport(true));
  runner.Run(Teleport(false));
  runner.Run(HighSpeed());
  runner.Run(Creep());
}

TEST(HardCases, InputExtremes) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  runner.Run(Quaternion(1.0, "quaternion-unit"));
  runner.Run(Quaternion(2.0, "quaternion-norm-2"));
  runner.Run(Quaternion(1e-3, "quaternion-norm-1e-3"));
  runner.Run(Quaternion(1e-200, "quaternion-near-zero"));
  runner.Run(Quaternion(0.0, "quaternion-zero"));
  // What a non-unit quaternion does (a precondition violation: Pose holds a unit quaternion,
  // and ParsePose and the UDP and plugin devices normalise): recorded, not checked.
  for (const std::string& name : ContactModelNames()) {
    for (int order = 0; order < 2; ++order) {
      const auto unit = Summary().first_force.find({name, "quaternion-unit", order});
      if (unit == Summary().first_force.end() || unit->second.norm() == 0) continue;
      for (const char* label : {"quaternion-norm-2", "quaternion-norm-1e-3", "quaternion-near-zero", "quaternion-zero"}) {
        const auto it = Summary().first_force.find({name, label, order});
        if (it == Summary().first_force.end()) continue;
        std::printf("quaternion %s %s %s: |F - F(unit)| / |F(unit)| = %.3g\n", name.c_str(), label,
                    order == 0 ? "AB" : "BA", (it->second - unit->second).norm() / unit->second.norm());
      }
    }
  }
  runner.Run(Scaled(1e-9, "scale-1e-9"));
  runner.Run(Scaled(1.0, "scale-1"));
  runner.Run(Scaled(1e3, "scale-1e3"));
  // The scaled scenes are similar to the unit one (bodies, pose and depth scaled by s) and the
  // penalty law is linear in depth: F(s) = s F(1). A model with an absolute length in it (a
  // margin, a tolerance) departs from it.
  for (const std::string& name : ContactModelNames()) {
    for (int order = 0; order < 2; ++order) {
      const auto unit = Summary().first_force.find({name, "scale-1", order});
      if (unit == Summary().first_force.end() || unit->second.norm() == 0) continue;
      for (const auto& [scale, label] : {std::pair{1e-9, "scale-1e-9"}, std::pair{1e3, "scale-1e3"}}) {
        const auto it = Summary().first_force.find({name, label, order});
        if (it == Summary().first_force.end()) continue;
        const double err = (it->second / scale - unit->second).norm() / unit->second.norm();
        const std::string order_name = order == 0 ? "AB" : "BA";
        std::printf("scaling %s %s %s: |F/s - F(1)| / |F(1)| = %.3g\n", name.c_str(), label, order_name.c_str(), err);
        if (err > 0.05) {
          if (const Finding* f = FindFinding(name, label, order, "scaling")) {
            std::printf("FINDING %s %s %s scaling: %.3g (%s)\n", name.c_str(), label, order_name.c_str(), err, f->reason);
          } else {
            ADD_FAILURE() << name << " " << label << " " << order_name << ": F(s)/s differs from F(1) by " << err
                          << " (|F(1)| " << unit->second.norm() << " N)";
          }
        }
      }
    }
  }
}

// CASE with body WHICH (1 or 2) deformable, a random deformation of up to 0.5 mm every cycle.
// Run in both orders, the deformable body is once the pointshell and once the field body.
HardCase Deformable(HardCase c, int which) {
  (which == 1 ? c.body1 : c.body2).deformable = true;
  c.name += which == 1 ? "-deformable-1" : "-deformable-2";
  c.deformation = 5e-4;
  return c;
}

// Deep penetration past the medial axis and a wall thinner than a voxel with deformable bodies
// (paper sec. 4): a deformable pointshell, and a deformed field whose pull-back reads the rest
// field far inside the body.
TEST(HardCases, DeformableBodiesThroughAPlateAndOverAPeg) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  for (const int which : {1, 2}) {
    runner.Run(Deformable(BallThroughPlate(), which));
    runner.Run(Deformable(TubeOverPeg(), which));
  }
}

// Fields of 8 and 128 cells along the longest side.
TEST(HardCases, FieldsOf8And128Cells) {
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  runner.Run(BallThroughPlate(8, 8, "fields-8"));
  runner.Run(BallThroughPlate(128, 128, "fields-128"));
}

// Fields of 512 cells: the ball's 512³ field has 134 M nodes (537 MB of floats), the plate's
// 512 x 512 x 35. About 35-70 s and 1.8 GB in the Release build, most of it VPS's 512³ voxmap;
// under AddressSanitizer it runs past ctest's 10-minute limit, and the same code is checked
// there at 8 and 128 cells.
TEST(HardCases, FieldsOf512Cells) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "512-cell fields take more than 10 minutes under AddressSanitizer; the Release suite runs them";
#endif
  RegisterContactModels();
  testing::TempDir cache;
  HardCaseRunner runner(cache);
  HardCase c = BallThroughPlate(512, 512, "fields-512");
  // pressure-field extracts its surface on the finer field's grid: a 0.05 mm lattice under a
  // 2 cm ball, 140,000 cells of surface, seconds per query. Every fourth grid line (0.2 mm) keeps
  // this case about the fields' size.
  c.model_keys = "pressure_lattice: 4";
  runner.Run(c);
}



// --- Tunnelling at speed (issue 33) --------------------------------------------------------
//
// A ball (r 1 cm), a blade (0.4 mm thick, edge first) and a tube (wall 0.5 mm, rim first)
// driven down through a 1 mm plate and a 0.5 mm wall at 0.1, 1, 5, 10 and 20 mm per cycle
// (0.1-20 m/s at 1 kHz), from 2 mm above to 2 mm past, in both role orders. Per model: did the
// tool get through (no force once it is wholly past the plate), the largest force, and whether
// the force on the tool ever pointed along its motion (pulling it through). A discrete model's
// result is a measurement, printed as a table; a proxy model (ContactModel::Proxy) must never
// let the tool through and its force must always push the tool back up.
struct TunnelTool {
  std::string name;
  BodyDef body;
  double half_height;  // m, from the tool's origin to its lowest point
};

std::vector<TunnelTool> TunnelTools() {
  return {{"ball", {"sphere:0.01,3", 48, 1024, 3}, 0.01},
          {"blade", {"box:0.02,0.0002,0.01,2", 192, 1024, 3}, 0.01},  // 0.25 mm cells: a zero crossing
          {"tube", {"tube:0.006,0.0055,0.015", 96, 2048, 3}, 0.015}};
}

TEST(HardCases, TunnellingAtSpeed) {
  RegisterContactModels();
  testing::TempDir cache;
  AssetOptions options;
  options.cache_dir = cache.path();
  options.verbose = false;
  const std::vector<std::pair<std::string, double>> plates = {{"plate-1mm", 0.0005}, {"wall-0.5mm", 0.00025}};
  int proxy_runs = 0;
  std::set<std::string> proxy_models;
  for (const TunnelTool& tool : TunnelTools()) {
    for (const auto& [plate_name, half] : plates) {
      HardCase c;
      c.name = "tunnelling-" + tool.name + "-" + plate_name;
      c.body1 = tool.body;
      c.body2 = {"box:0.03,0.03," + Num(half) + ",4", 192, 2048, 3};  // 0.375 mm cells: the wall has a zero crossing
      c.steps = {{Translation(0.0003, 0.0002, 0.05), Pose::Identity(), -1}};
      const Scene base = ParseScene(ConfigNode::LoadString(SceneText(c, 0), c.name + ".yaml"));
      for (int order = 0; order < 2; ++order) {
        const Scene scene = order == 0 ? base : base.Swapped();
        SceneAssets assets(scene, options);
        for (const std::string& name : ContactModelNames()) {
          if (name == "reference") continue;  // offline (ms-s per query)
          // The volumetric models are not in this experiment's comparison (docs/results-hard-cases.md, Tunnelling at
          // speed); like every discrete model they pull the ball through (hard-cases-medial-axis).
          if (name == "pressure-field" || name == "inner-spheres") continue;
          const std::unique_ptr<ContactModel> model = MakeOrExpectRefusal(name, c.name, order, scene, assets);
          if (!model) continue;
          for (const double step : {1e-4, 1e-3, 5e-3, 0.01, 0.02}) {
            // The tool's origin from (half + tool + 2 mm + step) above the plate's mid-plane to
            // as far below it.
            const double reach = half + tool.half_height + 0.002 + step;
            model->Reset();
            double peak = 0, last = 0;
            bool wrong_way = false, proxy = false;
            for (int i = 0;; ++i) {
              const double z = reach - step * i;
              if (z < -reach) break;
              const Pose X_tool = Translation(0.0003, 0.0002, z);
              ContactQuery q;
              q.X_WA = order == 0 ? X_tool : Pose::Identity();
              q.X_WB = order == 0 ? Pose::Identity() : X_tool;
              q.cycle = i;
              const ContactResult r = model->Evaluate(q);
              proxy = model->Proxy(nullptr);
              const Eigen::Vector3d on_tool = order == 0 ? Eigen::Vector3d(-r.on_B.force) : r.on_B.force;
              const double F = on_tool.norm();
              peak = std::max(peak, F);
              last = F;
              if (F > 1e-6 && on_tool.z() < -0.05 * F) wrong_way = true;  // along the tool's motion (-z)
              if (proxy && F > 1e-9) {
                EXPECT_GT(on_tool.z(), 0.5 * F) << name << " " << c.name << " order " << order << " step " << step
                                                << " cycle " << i << ": the proxy's force must push the tool back up";
              }
            }
            const bool through = last <= 1e-9;
            std::printf("tunnelling %-15s %-26s %s %5.1f mm/cycle: %s, peak %9.4g N%s\n", name.c_str(), c.name.c_str(),
                        order == 0 ? "AB" : "BA", step * 1e3, through ? "THROUGH" : "held   ", peak,
                        wrong_way ? ", pulled the wrong way" : "");
            if (proxy) {
              ++proxy_runs;
              proxy_models.insert(name);
              EXPECT_FALSE(through) << name << " " << c.name << " order " << order << " at " << step << " m per cycle";
              EXPECT_FALSE(wrong_way) << name << " " << c.name << " order " << order << " at " << step << " m per cycle";
            }
          }
        }
      }
    }
  }
  // The proxy model, pointshell-ccd, took every tool, plate, order and speed: 3 x 2 x 2 x 5
  // runs, each held (a refusal of one is a failure above, and would show here too).
  EXPECT_EQ(proxy_models, std::set<std::string>{"pointshell-ccd"});
  EXPECT_EQ(proxy_runs, int(TunnelTools().size()) * 2 * 2 * 5);
}

}  // namespace
}  // namespace contactlab
