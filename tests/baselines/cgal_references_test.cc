// Tests of the CGAL references: the dense-quadrature eq. (2) limit against the exact
// polyhedron-halfspace limit, exact signed distances, and the corefinement overlap volume and
// its gradient against boxes integrated by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "baselines/reference/analytic_references.h"
#include "baselines/reference/penetration_volume.h"
#include "baselines/reference/simplify_mesh.h"
#include "baselines/reference/halfspace_limit_reference.h"
#include "baselines/reference/surface_quadrature_reference.h"
#include "baselines/reference/volume_reference.h"
#include "contact/register_contact_models.h"
#include "contact/model_registry.h"
#include "geometry/procedural_shapes.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kC = 2000;
constexpr int kL = 10;

// A wide box B (top face z = 1/20 in its frame) yawed and shifted; its top as a halfspace.
struct WideBox {
  std::shared_ptr<const TriangleMesh> mesh =
      std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(1.0 / 10, 1.0 / 10, 1.0 / 20), 1));
  Pose X_WB{Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(0.01, -0.02, -0.05)};
  Eigen::Vector3d top_W() const { return X_WB * Eigen::Vector3d(0, 0, 1.0 / 20); }
};

TEST(QuadratureReference, MatchesExactPolyhedronHalfspaceLimitForTiltedBox) {
  WideBox B;
  auto A = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(1.0 / 30, 1.0 / 40, 1.0 / 50), 1));
  Pose X_WA;
  X_WA.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 0).normalized()));
  // Lowest corner 3 mm below the top face.
  double lowest = 1e9;
  for (const auto& v : A->vertices) lowest = std::min(lowest, (X_WA * v).z());
  X_WA.translation = Eigen::Vector3d(0.004, 0.002, -lowest - 0.003);
  QuadratureReferenceParams params;
  params.penalty.k_C = kC;
  params.penalty.L = kL;
  params.target_edge = 2e-4;
  QuadratureReference reference(A, B.mesh, params);
  const ForceLimit q = reference.Limit(X_WA, B.X_WB);
  const ForceLimit exact = PolyhedronHalfspaceLimit(*A, X_WA, B.top_W(), Eigen::Vector3d::UnitZ(), B.X_WB.translation,
                                                    kC, kL);
  ASSERT_GT(exact.on_B.force.norm(), 0);
  EXPECT_LT((q.on_B.force - exact.on_B.force).norm(), 0.02 * exact.on_B.force.norm())
      << q.on_B.force.transpose() << " vs " << exact.on_B.force.transpose();
  EXPECT_LT((q.on_B.torque - exact.on_B.torque).norm(), 0.02 * exact.on_B.torque.norm());
  EXPECT_NEAR(q.area_inside, exact.area_inside, 0.03 * exact.area_inside);
  EXPECT_NEAR(q.max_penetration, 0.003, 3e-4);
}

TEST(QuadratureReference, SignedDistanceIsExactForABox) {
  WideBox B;
  QuadratureReference reference(B.mesh, B.mesh, {});
  EXPECT_NEAR(reference.SignedDistance(Eigen::Vector3d(0.01, 0.02, 1.0 / 20 - 0.003)), -0.003, 1e-12);
  EXPECT_NEAR(reference.SignedDistance(Eigen::Vector3d(0.01, 0.02, 1.0 / 20 + 0.003)), 0.003, 1e-12);
  EXPECT_NEAR(reference.SignedDistance(Eigen::Vector3d(0.1 + 0.004, 0.1 + 0.003, 0)), 0.005, 1e-12);
}

TEST(QuadratureReference, HalfspaceGradientMatchesFiniteDifferencesForFlatContact) {
  // Box face on box face, moved by less than the gap between samples and B's surface.
  WideBox B;
  auto A = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(1.0 / 30, 1.0 / 40, 1.0 / 50), 1));
  QuadratureReferenceParams params;
  params.penalty.k_C = kC;
  params.penalty.L = kL;
  params.target_edge = 1e-3;
  QuadratureReference reference(A, B.mesh, params);
  ContactQuery q;
  q.X_WB = B.X_WB;
  q.X_WA.translation = B.top_W() + Eigen::Vector3d(0, 0, 1.0 / 50 - 0.002);
  const ContactResult r = reference.Evaluate(q);
  ASSERT_GT(r.stats.points_in_contact, 0);
  const double h = 1e-6;
  ContactQuery qp = q, qm = q;
  qp.X_WB.translation.z() += h;
  qm.X_WB.translation.z() -= h;
  const Eigen::Vector3d fd = (reference.Evaluate(qp).on_B.force - reference.Evaluate(qm).on_B.force) / (2 * h);
  // No sample crosses B's surface within ±h, so the inside area is fixed and every d moves
  // by -dz: the derivative is -k L Σ w N_z^2 / area, which is the halfspace rule.
  EXPECT_NEAR(fd.z(), r.K_B(2, 2), 1e-3 * std::abs(r.K_B(2, 2)));
  EXPECT_LT(r.K_B(2, 2), 0);
}

TEST(PenetrationVolume, OverlapOfBoxesIsProductOfOverlaps) {
  const TriangleMesh a = MakeBox(Eigen::Vector3d(1.0 / 30, 1.0 / 40, 1.0 / 50), 1);
  const TriangleMesh b = MakeBox(Eigen::Vector3d(1.0 / 10, 1.0 / 10, 1.0 / 20), 1);
  PenetrationVolume volume(a, b);
  const double delta = 0.002;
  const Pose X_WA = Pose::FromTranslation(Eigen::Vector3d(0.01, 0.02, 1.0 / 20 + 1.0 / 50 - delta));
  const Pose X_WB = Pose::Identity();
  const double area = 4.0 / 30 / 40;
  EXPECT_NEAR(volume.Volume(X_WA, X_WB), area * delta, 1e-9 * area * delta);
  // Moving B up by dz adds area dz; sideways and yaw add nothing. Rolling B about x by θ
  // lifts its top under A by y θ, so dV/dθx = ∫ y dA = 0.02 area; about y, -x θ: -0.01 area.
  const Vector6d g = volume.Gradient(X_WA, X_WB, 1e-4, 1e-3);
  EXPECT_NEAR(g[2], area, 1e-6 * area);
  EXPECT_NEAR(g[0], 0, 1e-9);
  EXPECT_NEAR(g[1], 0, 1e-9);
  EXPECT_NEAR(g[3], 0.02 * area, 0.01 * 0.02 * area);
  EXPECT_NEAR(g[4], -0.01 * area, 0.01 * 0.01 * area);
  EXPECT_NEAR(g[5], 0, 1e-9);
}

TEST(PenetrationVolume, SeparatedBodiesHaveZeroVolume) {
  const TriangleMesh s = MakeSphere(1.0 / 30, 2);
  PenetrationVolume volume(s, s);
  EXPECT_EQ(volume.Volume(Pose::Identity(), Pose::FromTranslation(Eigen::Vector3d(0.1, 0, 0))), 0.0);
}

TEST(PenetrationVolume, RejectsOpenMesh) {
  TriangleMesh open = MakeBox(Eigen::Vector3d(0.1, 0.1, 0.1), 1);
  open.triangles.pop_back();
  EXPECT_THROW(PenetrationVolume(open, open), Error);
}

// The volume law on a flat overlap: V = area * depth, so F_B = -k_V area z at every depth,
// with k_V = k_C L / sqrt(A's surface area); the torque is k_V times the first moments above.
TEST(VolumeReference, FlatOverlapGivesTheVolumeLawExactly) {
  auto a = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(1.0 / 30, 1.0 / 40, 1.0 / 50), 1));
  auto b = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(1.0 / 10, 1.0 / 10, 1.0 / 20), 1));
  PenaltyParams penalty;
  penalty.k_C = kC;
  penalty.L = kL;
  VolumeReference reference(a, b, penalty);
  const double surface = 8 * (1.0 / 30 / 40 + 1.0 / 30 / 50 + 1.0 / 40 / 50);
  EXPECT_NEAR(reference.k_V(), kC * kL / std::sqrt(surface), 1e-9 * reference.k_V());
  const double area = 4.0 / 30 / 40;
  for (double delta : {0.001, 0.004}) {
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.01, 0.02, 1.0 / 20 + 1.0 / 50 - delta));
    q.X_WB = Pose::Identity();
    const ContactResult r = reference.Evaluate(q);
    EXPECT_NEAR(r.on_B.force.z(), -reference.k_V() * area, 1e-6 * reference.k_V() * area) << delta;
    EXPECT_NEAR(r.on_B.force.head<2>().norm(), 0, 1e-6 * reference.k_V() * area);
    EXPECT_NEAR(r.on_B.torque.x(), -reference.k_V() * 0.02 * area, 0.01 * reference.k_V() * 0.02 * area);
    EXPECT_NEAR(r.on_B.torque.y(), reference.k_V() * 0.01 * area, 0.01 * reference.k_V() * 0.01 * area);
  }
  // Apart: no force, and no corefinement needed.
  ContactQuery apart;
  apart.X_WA = Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.2));
  EXPECT_EQ(reference.Evaluate(apart).on_B.force.norm(), 0.0);
}

// A sphere pressed into the box's top: -∇V is the face normal whatever the sphere's
// tessellation; the force grows with the overlap's cap area (2 pi r d, not with d alone).
TEST(VolumeReference, SphereIntoAFacePushesAlongTheNormalWithTheCapArea) {
  const double r = 1.0 / 40;
  auto a = std::make_shared<TriangleMesh>(MakeSphere(r, 4));
  auto b = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(1.0 / 10, 1.0 / 10, 1.0 / 20), 1));
  VolumeReference reference(a, b, PenaltyParams{});
  double previous = 0;
  for (double d : {0.002, 0.004, 0.008}) {
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.003, -0.002, 1.0 / 20 + r - d));
    const ContactResult res = reference.Evaluate(q);
    const Eigen::Vector3d F = res.on_B.force;
    EXPECT_LT(std::acos(std::clamp(-F.z() / F.norm(), -1.0, 1.0)), 0.5 * M_PI / 180) << d;
    // The cross-section of the sphere at the face: pi (2 r d - d^2) (the inscribed icosphere
    // of 5120 faces: within 3 %).
    EXPECT_NEAR(F.norm(), reference.k_V() * M_PI * (2 * r * d - d * d), 0.03 * F.norm()) << d;
    EXPECT_GT(F.norm(), previous);
    previous = F.norm();
  }
}

// The closed-form reference as a model: a sphere mesh stands for the exact sphere through its
// vertices; B's top face, wherever B is turned, is the halfspace.
TEST(HalfspaceLimitReference, SphereOnATurnedBoxMatchesTheClosedForm) {
  const double R = 0.05;
  auto sphere = std::make_shared<TriangleMesh>(MakeSphere(R, 2));
  sphere->name = "sphere:0.05,2";
  WideBox B;
  PenaltyParams penalty;
  penalty.k_C = kC;
  penalty.L = kL;
  HalfspaceLimitReference reference(sphere, B.mesh, penalty);
  const Eigen::Vector3d n = B.X_WB.rotation * Eigen::Vector3d::UnitZ();
  for (double depth : {0.0, 0.001, 0.004}) {
    ContactQuery q;
    q.X_WB = B.X_WB;
    q.X_WA = Pose::FromTranslation(B.top_W() + n * (R - depth) + Eigen::Vector3d(0.01, 0.005, 0));
    const ContactResult r = reference.Evaluate(q);
    if (depth == 0) {
      EXPECT_LT(r.on_B.force.norm(), 1e-9);  // touching: the closed form tends to 0
      continue;
    }
    const double expected = SphereHalfspaceForceMagnitude(R, R - depth, kC, kL);
    EXPECT_NEAR(r.on_B.force.dot(-n), expected, 1e-9 * expected) << depth;
    EXPECT_NEAR((r.on_B.force + expected * n).norm(), 0, 1e-9 * expected);
    EXPECT_NEAR(r.stats.max_penetration, depth, 1e-12);
  }
  // A sphere is not a box: refused as B.
  EXPECT_THROW(HalfspaceLimitReference(B.mesh, sphere, penalty), Error);
}

TEST(VolumeReference, IsAReferenceOnlyModel) {
  RegisterContactModels();
  const ContactModelEntry* e = FindContactModel("volume");
  ASSERT_NE(e, nullptr);
  EXPECT_TRUE(e->reference_only);
  for (const std::string& n : ContactModelNames()) EXPECT_NE(n, "volume");
  const std::vector<std::string> refs = ReferenceModelNames();
  EXPECT_NE(std::find(refs.begin(), refs.end(), "volume"), refs.end());
}

// Display thinning (the viewer's large meshes): a torus of 1/3 m and 1/9 m radii, 32,768
// triangles, thinned to 2,000 keeps to the budget (within the stop's rounding), stays a closed
// surface on the analytic torus (every vertex within 2% of the minor radius of it) and keeps
// its enclosed volume (2 pi^2 R r^2) within 3%.
TEST(SimplifyMesh, ThinnedTorusKeepsItsShapeAndTheBudget) {
  const double R = 1.0 / 3, r = 1.0 / 9;
  const TriangleMesh torus = MakeTorus(R, r, 256, 64);
  ASSERT_EQ(torus.num_triangles(), 32768);
  const TriangleMesh thin = SimplifyMesh(torus, 2000, "torus");
  EXPECT_LE(thin.num_triangles(), 2000);
  EXPECT_GE(thin.num_triangles(), 1900);
  double worst = 0;
  for (const Eigen::Vector3d& v : thin.vertices) {
    worst = std::max(worst, std::abs(std::hypot(std::hypot(v.x(), v.y()) - R, v.z()) - r));
  }
  EXPECT_LT(worst, 0.02 * r);
  const double volume = 2 * M_PI * M_PI * R * r * r;
  EXPECT_NEAR(std::abs(thin.SignedVolume()), volume, 0.03 * volume);
  // Still closed and oriented: each directed edge once, and its reverse once.
  std::map<std::pair<int, int>, int> directed;
  for (const Eigen::Vector3i& t : thin.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  int unmatched = 0;
  for (const auto& [e, n] : directed) unmatched += n != 1 || !directed.count({e.second, e.first});
  EXPECT_EQ(unmatched, 0);
  // A mesh within the budget comes back as it is; a budget below 4 is refused.
  EXPECT_EQ(SimplifyMesh(torus, 40000, "torus").triangles, torus.triangles);
  EXPECT_THROW(SimplifyMesh(torus, 3, "torus"), Error);
}

}  // namespace
}  // namespace contactlab
