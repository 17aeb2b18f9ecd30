// Characterization of every registered contact model (Drake-style): the same table of
// procedural shape pairs at non-trivial poses, sizes not exact in binary, each run as (A,B)
// and (B,A), against the references of the paper's eq. (2) limit (Barbič & James 2008,
// sec. 2.1): analytic where the pair has one (sphere-halfspace, sphere-sphere, polyhedron-
// halfspace), else the CGAL dense-quadrature limit for the magnitude and the CGAL overlap-
// volume gradient (-∇V) for the direction. Records the worst force direction error (degrees)
// and magnitude error (relative) per model and pair, and fails when a model gets worse than
// its recorded value (kRecorded below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "baselines/reference/analytic_references.h"
#include "baselines/register_baselines.h"
#include "experiment/scene_assets.h"
#include "experiment/scene.h"
#include "geometry/procedural_shapes.h"
#include "test_support.h"
#ifdef CONTACTLAB_HAVE_CGAL
#include "baselines/reference/penetration_volume.h"
#include "baselines/reference/surface_quadrature_reference.h"
#endif

namespace contactlab {
namespace {

constexpr double kC = 2000;
constexpr int kL = 10;
constexpr double kDepth = 1.0 / 300;  // penetration of every case, metres (3.33 mm)

// Worst errors per model and shape pair over both orders (A,B) and (B,A). To update after a
// deliberate change: run `test_baselines --gtest_filter='Characterization*'`, and paste the
// rows it prints ("recorded:" lines) here. A model or pair missing from the table is
// reported but not checked. The check allows 10 % + 1 degree and 10 % + 0.02 of slack.
struct Recorded {
  const char* model;
  const char* pair;
  double direction_deg;   // worst angle between the model's force on B and the reference's
  double magnitude_rel;   // worst | |F| - |F_ref| | / |F_ref|
};
const std::vector<Recorded> kRecorded = {
    // RECORDED-TABLE-BEGIN (Release build)
    {"bullet", "box-tilted/box", 0.68, 1.46},
    {"bullet", "capsule/torus", 3.95, 0.532},
    {"bullet", "sphere/box-halfspace", 0.57, 0.017},
    {"bullet", "sphere/sphere", 0.23, 0.01},
    {"fcl", "box-tilted/box", 0.01, 1.74},
    {"fcl", "capsule/torus", 2.23, 0.676},
    {"fcl", "sphere/box-halfspace", 0.01, 0.461},
    {"fcl", "sphere/sphere", 4.21, 0.697},
    {"pointshell", "box-tilted/box", 2.23, 0.133},
    {"pointshell", "capsule/torus", 0.64, 0.042},
    {"pointshell", "sphere/box-halfspace", 0.13, 0.038},
    {"pointshell", "sphere/sphere", 0.42, 0.012},
    {"pointshell-linear", "box-tilted/box", 2.23, 0.133},
    {"pointshell-linear", "capsule/torus", 0.64, 0.042},
    {"pointshell-linear", "sphere/box-halfspace", 0.13, 0.038},
    {"pointshell-linear", "sphere/sphere", 0.42, 0.012},
    {"vps", "box-tilted/box", 58.5, 0.239},
    {"vps", "capsule/torus", 4.45, 0.552},
    {"vps", "sphere/box-halfspace", 1.73, 0.467},
    {"vps", "sphere/sphere", 0.68, 0.502},
    {"vps-repulsion", "box-tilted/box", 5.58, 0.281},
    {"vps-repulsion", "capsule/torus", 1.29, 0.325},
    {"vps-repulsion", "sphere/box-halfspace", 0.25, 0.448},
    {"vps-repulsion", "sphere/sphere", 0.47, 0.506},
    // RECORDED-TABLE-END
};

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// A pose with rotation vector W (radians) and translation T.
Pose MakePose(const Eigen::Vector3d& w, const Eigen::Vector3d& t) { return {RotationFromVector(w), t}; }

// The world frame every case is expressed in, so no face is axis-aligned.
const Pose kWorld = MakePose(Eigen::Vector3d(0.3, -0.5, 0.7), Eigen::Vector3d(0.01 / 3, -0.02 / 3, 0.1 / 7));

enum class Reference { kPolyhedronHalfspace, kSphereSphere, kCgal };

struct Body {
  std::string mesh;  // procedural spec
  Pose pose;         // in the case's local frame
  // Sphere centre and radius, for the sphere-sphere reference.
  double radius = 0;
};

struct PairCase {
  std::string pair;
  Body first, second;
  // Reference when FIRST is the pointshell body A; the swapped order uses the CGAL one,
  // except for sphere-sphere which is symmetric.
  Reference reference;
  Eigen::Vector3d halfspace_top_local;  // SECOND's top face (plane z = top in SECOND's frame)
};

std::vector<PairCase> Cases() {
  std::vector<PairCase> cases;
  const double r = 1.0 / 30;
  // Sphere pressed kDepth into a box used as a halfspace (its top face, z = 1/40).
  {
    PairCase c;
    c.pair = "sphere/box-halfspace";
    c.first = {"sphere:" + Num(r) + ",3", MakePose(Eigen::Vector3d(0.2, 0.1, 0), Eigen::Vector3d(0.004, -0.003, 1.0 / 40 + r - kDepth)), r};
    c.second = {"box:" + Num(1.0 / 15) + "," + Num(1.0 / 15) + "," + Num(1.0 / 40) + ",4", Pose::Identity()};
    c.reference = Reference::kPolyhedronHalfspace;
    c.halfspace_top_local = Eigen::Vector3d(0, 0, 1.0 / 40);
    cases.push_back(c);
  }
  // Two spheres overlapping by kDepth along a skew axis.
  {
    PairCase c;
    c.pair = "sphere/sphere";
    const double rb = 1.0 / 24;
    const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
    c.first = {"sphere:" + Num(r) + ",4", MakePose(Eigen::Vector3d(0.1, 0.2, 0.3), -(r + rb - kDepth) * axis), r};
    c.second = {"sphere:" + Num(rb) + ",4", MakePose(Eigen::Vector3d(-0.2, 0, 0.1), Eigen::Vector3d::Zero()), rb};
    c.reference = Reference::kSphereSphere;
    cases.push_back(c);
  }
  // A tilted box whose lowest corner is kDepth below a wide box's top face.
  {
    PairCase c;
    c.pair = "box-tilted/box";
    const Eigen::Vector3d half(1.0 / 30, 1.0 / 40, 1.0 / 50);
    const Pose tilt = MakePose(0.3 * Eigen::Vector3d(1, 2, 0).normalized(), Eigen::Vector3d::Zero());
    double lowest = 1e9;
    for (const auto& v : MakeBox(half, 1).vertices) lowest = std::min(lowest, (tilt * v).z());
    Pose pose = tilt;
    pose.translation = Eigen::Vector3d(0.003, 0.002, 1.0 / 40 - lowest - kDepth);
    c.first = {"box:" + Num(half.x()) + "," + Num(half.y()) + "," + Num(half.z()) + ",3", pose};
    c.second = {"box:" + Num(1.0 / 12) + "," + Num(1.0 / 12) + "," + Num(1.0 / 40) + ",4", Pose::Identity()};
    c.reference = Reference::kPolyhedronHalfspace;
    c.halfspace_top_local = Eigen::Vector3d(0, 0, 1.0 / 40);
    cases.push_back(c);
  }
  // A capsule lying across a torus tube, kDepth into it (no analytic reference).
  {
    PairCase c;
    c.pair = "capsule/torus";
    const double R = 1.0 / 60, H = 1.0 / 30, major = 1.0 / 20, minor = 1.0 / 60;
    const Pose across = MakePose(Eigen::Vector3d(0, M_PI / 2, 0), Eigen::Vector3d(major, 0, minor + R - kDepth));
    c.first = {"capsule:" + Num(R) + "," + Num(H), across};
    c.second = {"torus:" + Num(major) + "," + Num(minor), Pose::Identity()};
    c.reference = Reference::kCgal;
    cases.push_back(c);
  }
  return cases;
}

BodySpec MakeBodySpec(const std::string& name, const Body& body, const std::string& role) {
  BodySpec b;
  b.name = name;
  b.mesh = body.mesh;
  b.pose = kWorld * body.pose;
  b.role = role;
  b.field.resolution = 64;
  b.pointshell.points = 4096;
  b.pointshell.levels = 3;
  b.pointshell.offset = 0;  // points on the surface: measure the contact model, not the offset
  return b;
}

struct Measured {
  double direction_deg = 0;
  double magnitude_rel = 0;
};

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (a.norm() == 0 || b.norm() == 0) return 180;
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

TEST(Characterization, EveryModelWithinRecordedErrorOfReferences) {
  RegisterBaselineContactModels();
  testing::TempDir cache;
  AssetOptions options;
  options.cache_dir = cache.path();
  options.verbose = false;

  std::map<std::pair<std::string, std::string>, Measured> worst;  // (model, pair)
  for (const PairCase& c : Cases()) {
    for (int order = 0; order < 2; ++order) {
      const Body& a = order == 0 ? c.first : c.second;
      const Body& b = order == 0 ? c.second : c.first;
      Scene scene;
      scene.name = c.pair + (order == 0 ? " (A,B)" : " (B,A)");
      scene.pointshell_body = MakeBodySpec("A", a, "pointshell");
      scene.field_body = MakeBodySpec("B", b, "field");
      scene.model.penalty.k_C = kC;
      scene.model.penalty.L = kL;
      SceneAssets assets(scene, options);
      const Pose X_WA = scene.pointshell_body.pose, X_WB = scene.field_body.pose;

      // The reference force on B and the reference direction.
      std::optional<Eigen::Vector3d> F_ref, direction_ref;
      if (c.reference == Reference::kSphereSphere) {
        F_ref = SphereSphereLimit(X_WA.translation, a.radius, X_WB.translation, b.radius, X_WB.translation, kC, kL)
                    .on_B.force;
      } else if (c.reference == Reference::kPolyhedronHalfspace && order == 0) {
        const Eigen::Vector3d q_W = X_WB * c.halfspace_top_local;
        const Eigen::Vector3d n_W = X_WB.R() * Eigen::Vector3d::UnitZ();
        F_ref = PolyhedronHalfspaceLimit(*assets.A.mesh(), X_WA, q_W, n_W, X_WB.translation, kC, kL).on_B.force;
      } else {
#ifdef CONTACTLAB_HAVE_CGAL
        QuadratureReferenceParams params;
        params.penalty.k_C = kC;
        params.penalty.L = kL;
        params.target_edge = 7e-4;
        F_ref = QuadratureReference(assets.A.mesh(), assets.B.mesh(), params).Limit(X_WA, X_WB).on_B.force;
        const Vector6d g = PenetrationVolume(*assets.A.mesh(), *assets.B.mesh()).Gradient(X_WA, X_WB, 1e-4, 1e-3, false);
        direction_ref = -g.head<3>();
#else
        std::cout << scene.name << ": skipped, needs CGAL for its reference\n";
        continue;
#endif
      }
      if (!direction_ref) direction_ref = *F_ref;
      ASSERT_GT(F_ref->norm(), 0) << scene.name;

      // Every registered model on the same query.
      for (const std::string& name : ContactModelNames()) {
        if (name == "reference") continue;  // the quadrature reference itself
        std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, scene, assets);
        ContactQuery q;
        q.X_WA = X_WA;
        q.X_WB = X_WB;
        const ContactResult r = model->Evaluate(q);
        Measured m;
        m.direction_deg = AngleDeg(r.on_B.force, *direction_ref);
        m.magnitude_rel = std::abs(r.on_B.force.norm() - F_ref->norm()) / F_ref->norm();
        std::cout << scene.name << " " << name << ": direction " << m.direction_deg << " deg, magnitude "
                  << m.magnitude_rel << " (|F| " << r.on_B.force.norm() << " N vs " << F_ref->norm() << " N, "
                  << r.stats.points_in_contact << " contacts)\n";
        Measured& w = worst[{name, c.pair}];
        w.direction_deg = std::max(w.direction_deg, m.direction_deg);
        w.magnitude_rel = std::max(w.magnitude_rel, m.magnitude_rel);
      }
    }
  }

  // Compare with the recorded table, and print rows to paste into it.
  for (const auto& [key, m] : worst) {
    const auto& [model, pair] = key;
    char row[200];
    std::snprintf(row, sizeof row, "    {\"%s\", \"%s\", %.3g, %.3g},", model.c_str(), pair.c_str(),
                  std::ceil(m.direction_deg * 100) / 100, std::ceil(m.magnitude_rel * 1000) / 1000);
    std::cout << "recorded:" << row << "\n";
    const Recorded* rec = nullptr;
    for (const Recorded& r : kRecorded) {
      if (model == r.model && pair == r.pair) rec = &r;
    }
    if (!rec) {
      std::cout << "  (no recorded row for " << model << " on " << pair << ": not checked)\n";
      continue;
    }
    EXPECT_LE(m.direction_deg, 1.1 * rec->direction_deg + 1.0) << model << " on " << pair;
    EXPECT_LE(m.magnitude_rel, 1.1 * rec->magnitude_rel + 0.02) << model << " on " << pair;
  }
}

}  // namespace
}  // namespace contactlab
