#include "pointshell_contact/pointshell_contact_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <span>

#include "allocation_counter.h"
#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "sdf/signed_distance_grid.h"
#include "contact/test_shells.h"
#include "pointshell_contact/wrench_finite_differences.h"
#include "util/error.h"

namespace contactlab {
namespace {

using Variant = PointshellContactModel::Variant;
using testing::SampleField;
using testing::SphereShell;

// Field of a sphere of radius R at the origin, on a grid of spacing H.
std::shared_ptr<DistanceField> SphereField(double R, double h) {
  const Eigen::Vector3d lo = Eigen::Vector3d::Constant(-1.3 * R), hi = Eigen::Vector3d::Constant(1.3 * R);
  return SampleField([R](const Eigen::Vector3d& p) { return p.norm() - R; }, lo, hi, h);
}

// Field of the halfspace z < 0 over a slab around the plane.
std::shared_ptr<DistanceField> HalfspaceField(double half_width, double h) {
  // The box encloses everything the tests put above the plane, so no point is outside it.
  return SampleField([](const Eigen::Vector3d& p) { return p.z(); }, Eigen::Vector3d(-half_width, -half_width, -0.3 * half_width),
                     Eigen::Vector3d(half_width, half_width, half_width), h);
}

Pose RandomPose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  return {RotationFromVector(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5),
          spread * Eigen::Vector3d(u(rng), u(rng), u(rng))};
}

// The same points in contact, and the wrench to relative REL. The forces are summed in float
// (contact/halfspace_contacts.h), so two traversals that meet the points in another order
// agree to about 1e-7; one point more or less would change the force by far more than 1e-5.
// Torques are compared on the scale of the force times the tests' lever arm (0.1 m).
void ExpectWrenchNear(const ContactResult& a, const ContactResult& b, double rel) {
  const double scale = std::max(1e-12, a.on_B.force.norm());
  EXPECT_LT((a.on_B.force - b.on_B.force).norm(), rel * scale) << a.on_B.force.transpose() << " vs " << b.on_B.force.transpose();
  EXPECT_LT((a.on_B.torque - b.on_B.torque).norm(), rel * (a.on_B.torque.norm() + 0.1 * scale));
  EXPECT_EQ(a.stats.points_in_contact, b.stats.points_in_contact);
}

TEST(PointshellContactModel, TreeTraversalEqualsLinearTraversalOfTheSameLevel) {
  auto shell = SphereShell(0.05, 48, 4);
  auto field = SphereField(0.06, 0.004);
  int contacts_seen = 0;
  for (int level = 0; level < 4; ++level) {
    PointshellContactParams params;
    params.level = level;
    PointshellContactModel linear(Variant::kLinear, shell, field, params);
    PointshellContactModel tree(Variant::kTree, shell, field, params);
    std::mt19937 rng(100 + level);
    for (int trial = 0; trial < 40; ++trial) {
      ContactQuery q;
      q.X_WB = RandomPose(rng, 0.02);
      // A's centre 0.09..0.11 from B's centre: shallow to deep contact of the two spheres.
      const Eigen::Vector3d dir = Eigen::Vector3d::Random().normalized();
      q.X_WA = {RotationFromVector(Eigen::Vector3d::Random()), q.X_WB.translation + (0.095 + 0.01 * trial / 40.0) * dir};
      const ContactResult rl = linear.Evaluate(q);
      const ContactResult rt = tree.Evaluate(q);
      ExpectWrenchNear(rl, rt, 1e-5);
      EXPECT_EQ(rt.stats.level_rendered, level);
      EXPECT_LE(rt.stats.nodes_visited, shell->level_node_begin[level + 1]);
      contacts_seen += rl.stats.points_in_contact > 0;
    }
  }
  EXPECT_GT(contacts_seen, 100);
}

// A sparse field behind the model: in shallow contact (within the band) the wrench equals the
// dense field's on the same grid to the 16-bit step, and the tree still equals the linear
// traversal (its culling holds on the sparse field's bounds).
TEST(PointshellContactModel, SparseFieldGivesTheDenseWrenchInTheBandAndTreeEqualsLinear) {
  TriangleMesh ball = MakeSphere(0.06, 5);
  ball.name = "ball";
  DistanceFieldOptions o;
  o.resolution = 128;
  o.storage = FieldStorage::kSparse;
  o.show_progress = false;
  auto sparse = std::make_shared<DistanceField>(BuildDistanceField(ball, o));
  FieldGrid grid;
  grid.origin = sparse->origin();
  grid.spacing = sparse->spacing();
  grid.dims = sparse->dims();
  auto dense = std::make_shared<DistanceField>(grid.origin, grid.spacing, grid.dims, ComputeSignedDistance(ball, grid, 3));
  const double h = sparse->spacing();
  auto shell = SphereShell(0.05, 48, 4);
  PointshellContactParams params;
  PointshellContactModel tree_sparse(Variant::kTree, shell, sparse, params);
  PointshellContactModel linear_sparse(Variant::kLinear, shell, sparse, params);
  PointshellContactModel tree_dense(Variant::kTree, shell, dense, params);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  int contacts = 0;
  for (int trial = 0; trial < 60; ++trial) {
    ContactQuery q;
    q.X_WB = RandomPose(rng, 0.01);
    const Eigen::Vector3d dir = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    // Penetration up to 2 voxels: every point in contact reads fine samples.
    q.X_WA = {RotationFromVector(Eigen::Vector3d::Random()), q.X_WB.translation + (0.11 - 2 * h * u(rng)) * dir};
    const ContactResult rs = tree_sparse.Evaluate(q), rl = linear_sparse.Evaluate(q), rd = tree_dense.Evaluate(q);
    ExpectWrenchNear(rs, rl, 1e-5);
    // A point within a 16-bit step of d = 0 may fall either side; the wrench depends on the
    // count of points in contact (the stiffness is shared among them), so compare wrenches
    // where the counts agree.
    EXPECT_NEAR(rs.stats.points_in_contact, rd.stats.points_in_contact, 1) << "trial " << trial;
    if (rd.stats.points_in_contact == 0 || rs.stats.points_in_contact != rd.stats.points_in_contact) continue;
    ++contacts;
    // Relative, with a floor of 1 mN (a 16-bit step on a few points of very shallow contact;
    // typical forces here are a few N). Two spheres: the torque about B's origin is near zero,
    // so it is held to the force's tolerance times the lever arm (0.11 m), not its own size.
    const double tolerance = 1e-3 * rd.on_B.force.norm() + 1e-3;
    EXPECT_LT((rs.on_B.force - rd.on_B.force).norm(), tolerance) << "trial " << trial;
    EXPECT_LT((rs.on_B.torque - rd.on_B.torque).norm(), 0.11 * tolerance) << "trial " << trial;
  }
  EXPECT_GT(contacts, 35);
}

TEST(PointshellContactModel, TemporalCoherenceGivesIdenticalResultsWithinTheSpeedBound) {
  auto shell = SphereShell(0.05, 48, 4);
  auto field = SphereField(0.06, 0.004);
  PointshellContactParams params;
  params.max_point_speed = 0.5;  // m/s
  PointshellContactModel plain(Variant::kTree, shell, field, params);
  params.coherence = true;
  PointshellContactModel coherent(Variant::kTree, shell, field, params);
  // A random trajectory: A's centre wanders in and out of contact; no point of A moves faster
  // than 0.5 m/s relative to B (translation speed + angular speed * radius, checked below).
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  Eigen::Vector3d c(0.13, 0, 0), v(0, 0, 0), w(0, 0, 0);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const double dt = params.cycle_seconds;
  std::int64_t skipped = 0;
  int contact_cycles = 0;
  for (int cycle = 0; cycle < 3000; ++cycle) {
    // Random accelerations, speeds capped: |v| <= 0.3, |w| * R <= 0.15 (R = 0.05).
    v += 0.02 * Eigen::Vector3d(g(rng), g(rng), g(rng)) - 0.002 * (c - Eigen::Vector3d(0.1, 0, 0)) / dt * dt * 1000;
    if (v.norm() > 0.3) v *= 0.3 / v.norm();
    w += 0.5 * Eigen::Vector3d(g(rng), g(rng), g(rng));
    if (w.norm() > 3.0) w *= 3.0 / w.norm();
    c += v * dt;
    q = (RotationFromVector(w * dt) * q).normalized();
    ContactQuery query;
    query.cycle = cycle;
    query.X_WA = {q, c};
    const ContactResult a = plain.Evaluate(query);
    const ContactResult b = coherent.Evaluate(query);
    ASSERT_EQ(a.on_B.force, b.on_B.force) << "cycle " << cycle;
    ASSERT_EQ(a.on_B.torque, b.on_B.torque) << "cycle " << cycle;
    skipped += b.stats.nodes_skipped_coherence;
    contact_cycles += a.stats.points_in_contact > 0;
  }
  EXPECT_GT(contact_cycles, 300);
  EXPECT_GT(skipped, 1000) << "coherence never skipped anything";
}

TEST(PointshellContactModel, DegradationRendersTheDeepestLevelThatFitsAndHoldsIt) {
  auto shell = SphereShell(0.05, 48, 4);
  auto field = SphereField(0.06, 0.004);
  ContactQuery q;
  q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.1, 0.001, -0.002));
  PointshellContactParams params;
  PointshellContactModel full(Variant::kTree, shell, field, params);
  const ContactResult unlimited = full.Evaluate(q);
  ASSERT_EQ(unlimited.stats.level_rendered, 3);
  EXPECT_EQ(unlimited.stats.degraded, 0);
  const std::int64_t need = unlimited.stats.nodes_visited;
  // With exactly enough budget for everything, the deepest level is rendered (warm after the first cycle).
  for (std::int64_t budget : {need / 3, need / 2, need, 2 * need}) {
    PointshellContactModel model(Variant::kTree, shell, field, params);
    q.node_budget = budget;
    std::vector<int> levels;
    for (int cycle = 0; cycle < 20; ++cycle) {
      q.cycle = cycle;
      const ContactResult r = model.Evaluate(q);
      levels.push_back(r.stats.level_rendered);
      // The degradation stat: the levels the budget left out.
      EXPECT_EQ(r.stats.degraded, 3 - r.stats.level_rendered);
      EXPECT_LE(r.stats.nodes_visited, std::max<std::int64_t>(budget, shell->level_node_begin[1]));
      // The forces equal a linear traversal of the rendered level.
      PointshellContactParams lp = params;
      lp.level = r.stats.level_rendered;
      PointshellContactModel linear(Variant::kLinear, shell, field, lp);
      ExpectWrenchNear(linear.Evaluate(q), r, 1e-5);
    }
    for (int lv : levels) EXPECT_EQ(lv, levels.back()) << "level changed on a still pose, budget " << budget;
    // Deepest that fits: one level deeper would exceed the cold threshold.
    if (levels.back() < 3) {
      PointshellContactParams lp = params;
      lp.level = levels.back() + 1;
      PointshellContactModel deeper(Variant::kTree, shell, field, lp);
      ContactQuery uq = q;
      uq.node_budget = 0;
      EXPECT_GT(double(deeper.Evaluate(uq).stats.nodes_visited), 0.8 * double(budget) - shell->level_node_begin[1]);
    }
  }
}

TEST(PointshellContactModel, HysteresisKeepsAWarmLevelThatAColdStartWouldNotEnter) {
  auto shell = SphereShell(0.05, 48, 4);
  auto field = SphereField(0.06, 0.004);
  ContactQuery q;
  q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.1, 0.0, 0.0));
  PointshellContactModel model(Variant::kTree, shell, field, {});
  const std::int64_t need = model.Evaluate(q).stats.nodes_visited;
  // Budget between need and need / 0.8: a cold start may not enter the deepest level, but once
  // it was rendered (warm) it stays.
  q.node_budget = std::int64_t(need / 0.9);
  model.Reset();
  const int cold_level = model.Evaluate(q).stats.level_rendered;
  EXPECT_LT(cold_level, 3);
  PointshellContactModel warm(Variant::kTree, shell, field, {});
  q.node_budget = 0;
  warm.Evaluate(q);  // renders level 3 unlimited
  q.node_budget = std::int64_t(need / 0.9);
  for (int c = 0; c < 5; ++c) EXPECT_EQ(warm.Evaluate(q).stats.level_rendered, 3);
}

// Paper eq. (2) for a sphere of radius R whose centre is at height h above the plane, with the
// L / l scaling: |F| = k_C L R (R/3 - h/2 + h^3/(6 R^2)) / (R - h), directed away from the sphere.
double SphereHalfspaceLimit(double k, int L, double R, double h) {
  return k * L * R * (R / 3 - h / 2 + h * h * h / (6 * R * R)) / (R - h);
}

TEST(PointshellContactModel, SpherePressedIntoHalfspaceConvergesToTheVolumeIntegralLimit) {
  const double R = 0.05, h = 0.042, k = 500;
  auto field = HalfspaceField(0.1, 0.005);  // exact for a plane: trilinear reproduces d = z
  const double limit = SphereHalfspaceLimit(k, 10, R, h);
  std::vector<double> errors;
  for (int n : {500, 2000, 8000, 32000}) {
    std::vector<Eigen::Vector3d> p, nn;
    testing::FibonacciSphere(R, n, 1, &p, &nn, false);
    auto shell = testing::MakeNestedShell(p, nn, {n});
    PointshellContactModel model(Variant::kLinear, shell, field, {.penalty = {.k_C = k, .L = 10}});
    // Average over a few rotations of the sphere to remove the lattice's orientation bias.
    Eigen::Vector3d F = Eigen::Vector3d::Zero();
    const int rotations = 8;
    for (int r = 0; r < rotations; ++r) {
      ContactQuery q;
      q.X_WA = {RotationFromVector(Eigen::Vector3d(0.3 * r, 1.1 * r, 0.7)), Eigen::Vector3d(0.001, -0.002, h)};
      const ContactResult res = model.Evaluate(q);
      F += res.on_B.force / rotations;
      // Moment about the sphere centre vanishes: every force acts along a normal through it.
      const Eigen::Vector3d moment_c = res.on_B.torque - q.X_WA.translation.cross(res.on_B.force);
      EXPECT_LT(moment_c.norm(), 1e-6 * R * res.on_B.force.norm());  // float positions
    }
    EXPECT_LT(F.z(), 0) << "the force on the halfspace must point away from the sphere";
    EXPECT_LT(std::hypot(F.x(), F.y()), 0.02 * std::abs(F.z()));
    errors.push_back(std::abs(-F.z() - limit) / limit);
  }
  for (std::size_t i = 0; i < errors.size(); ++i) std::printf("points %d: relative error %.5f\n", 500 << (2 * i), errors[i]);
  EXPECT_LT(errors.back(), 0.01);
  EXPECT_LT(errors.back(), errors.front());
}

TEST(PointshellContactModel, RoleReversalOnTwoSpheresAgreesAsResolutionGrows) {
  const double Ra = 0.04, Rb = 0.06;
  const double gap = Ra + Rb - 0.004;  // 4 mm overlap
  std::vector<double> diffs;
  for (auto [n, h] : {std::pair{1000, 0.006}, std::pair{4000, 0.003}, std::pair{16000, 0.0015}}) {
    auto fa = SphereField(Ra, h), fb = SphereField(Rb, h);
    std::vector<Eigen::Vector3d> p, nn;
    testing::FibonacciSphere(Ra, n, 2, &p, &nn, false);
    auto sa = testing::MakeNestedShell(p, nn, {n});
    p.clear(), nn.clear();
    testing::FibonacciSphere(Rb, int(n * (Rb * Rb) / (Ra * Ra)), 3, &p, &nn, false);
    auto sb = testing::MakeNestedShell(p, nn, {int(p.size())});
    PointshellContactParams params{.penalty = {.k_C = 800, .L = 10}};
    // Sphere a is the pointshell, b the field; then the reverse. Compare the force on b.
    PointshellContactModel ab(Variant::kLinear, sa, fb, params), ba(Variant::kLinear, sb, fa, params);
    ContactQuery q1;
    q1.X_WA = Pose::FromTranslation(Eigen::Vector3d(gap, 0, 0));
    const Eigen::Vector3d F_b1 = ab.Evaluate(q1).on_B.force;
    ContactQuery q2;
    q2.X_WB = Pose::FromTranslation(Eigen::Vector3d(gap, 0, 0));
    const Eigen::Vector3d F_b2 = -ba.Evaluate(q2).on_B.force;  // force on the pointshell body b
    ASSERT_GT(F_b1.norm(), 0);
    diffs.push_back((F_b1 - F_b2).norm() / F_b1.norm());
    std::printf("n %d h %.4f: force on b %.4f vs %.4f (rel diff %.4f)\n", n, h, F_b1.x(), F_b2.x(), diffs.back());
  }
  EXPECT_LT(diffs.back(), 0.1);
  EXPECT_LT(diffs.back(), diffs.front() + 1e-3);
}

using testing::FiniteDifferenceGradient;

TEST(PointshellContactModel, FieldGradientMatchesFiniteDifferences) {
  auto shell = SphereShell(0.05, 200, 1);
  auto field = SphereField(0.06, 0.002);
  PointshellContactParams params{.penalty = {.k_C = 1000, .L = 0}, .gradient = ContactGradient::kField};
  PointshellContactModel model(Variant::kLinear, shell, field, params);
  ContactQuery q;
  q.X_WB = {RotationFromVector(Eigen::Vector3d(0.2, -0.1, 0.4)), Eigen::Vector3d(0.01, 0.02, -1.0 / 300)};
  q.X_WA = {RotationFromVector(Eigen::Vector3d(-0.3, 0.5, 0.1)), q.X_WB.translation + Eigen::Vector3d(0.06, 0.07, 0.03)};
  const ContactResult r = model.Evaluate(q);
  ASSERT_GT(r.stats.points_in_contact, 5);
  const Matrix6d fd = FiniteDifferenceGradient(model, q, 2e-5);
  EXPECT_LT((r.K_B - fd).norm(), 2e-2 * fd.norm()) << "analytic\n" << r.K_B << "\nfd\n" << fd;
}

TEST(PointshellContactModel, HalfspaceGradientIsExactForFlatContact) {
  // A square patch of points facing down (inward normal +z) on the halfspace field: the
  // halfspace rule then equals the exact derivative.
  std::vector<Eigen::Vector3d> p, n;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      p.emplace_back(-0.02 + 0.002 * i, -0.02 + 0.002 * j, 0);
      n.emplace_back(0, 0, 1);
    }
  auto shell = testing::MakeNestedShell(p, n, {400});
  auto field = HalfspaceField(0.1, 0.01);
  PointshellContactModel model(Variant::kLinear, shell, field, {.penalty = {.k_C = 300, .L = 0}});
  ContactQuery q;
  // B turned about the plane normal only, so the plane stays parallel to the patch.
  q.X_WB = {RotationFromVector(Eigen::Vector3d(0, 0, 0.3)), Eigen::Vector3d(0.003, -0.001, 0.002)};
  q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.004, 0.002, 0.0005));
  const ContactResult r = model.Evaluate(q);
  ASSERT_EQ(r.stats.points_in_contact, 400);
  const Matrix6d fd = FiniteDifferenceGradient(model, q, 1e-4);
  EXPECT_LT((r.K_B - fd).norm(), 1e-3 * fd.norm()) << "analytic\n" << r.K_B << "\nfd\n" << fd;
}

TEST(PointshellContactModel, ManyPointScalingDividesStiffnessByLOverL) {
  std::vector<Eigen::Vector3d> p, n;
  for (int i = 0; i < 40; ++i) {
    p.emplace_back(0.001 * i, 0, 0);
    n.emplace_back(0, 0, 1);
  }
  auto shell = testing::MakeNestedShell(p, n, {40});
  auto field = HalfspaceField(0.1, 0.01);
  ContactQuery q;
  q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0, 0, -0.001));  // every point 1 mm deep
  PointshellContactModel scaled(Variant::kLinear, shell, field, {.penalty = {.k_C = 100, .L = 10}});
  PointshellContactModel unscaled(Variant::kLinear, shell, field, {.penalty = {.k_C = 100, .L = 0}});
  const ContactResult rs = scaled.Evaluate(q), ru = unscaled.Evaluate(q);
  EXPECT_NEAR(ru.on_B.force.z(), -40 * 100 * 0.001, 1e-5);  // d is a float
  EXPECT_NEAR(rs.on_B.force.z(), -10 * 100 * 0.001, 1e-5);  // k L / l * l * d = k L d
  EXPECT_NEAR(rs.stats.stiffness_scale, 0.25, 1e-12);
}

TEST(PointshellContactModel, InvalidParametersAreRejected) {
  auto shell = SphereShell(0.05, 48, 2);
  auto field = SphereField(0.06, 0.01);
  EXPECT_THROW(PointshellContactModel(Variant::kTree, shell, field, {.penalty = {.k_C = -1}}), Error);
  PointshellContactParams bad_level;
  bad_level.level = 2;
  EXPECT_THROW(PointshellContactModel(Variant::kTree, shell, field, bad_level), Error);
  PointshellContactParams bad_speed;
  bad_speed.max_point_speed = 0;
  EXPECT_THROW(PointshellContactModel(Variant::kTree, shell, field, bad_speed), Error);
  EXPECT_THROW(PointshellContactModel(Variant::kTree, nullptr, field, {}), Error);
}

}  // namespace
}  // namespace contactlab

namespace contactlab {
namespace {

// The haptic-cycle rule: Evaluate allocates nothing, for either variant, with coherence and
// a node budget that makes the level change.
// The two variants of the allocation tests over one shell and field: the tree with coherence,
// the linear traversal with the defaults.
struct SlidingPair {
  std::shared_ptr<const Pointshell> shell = testing::SphereShell(0.05, 48, 4);
  std::shared_ptr<const DistanceField> field = SphereField(0.06, 0.004);
  PointshellContactModel tree{PointshellContactModel::Variant::kTree, shell, field, [] {
                                PointshellContactParams p;
                                p.coherence = true;
                                return p;
                              }()};
  PointshellContactModel linear{PointshellContactModel::Variant::kLinear, shell, field, {}};
};

// 2000 cycles of body A sliding in and out of the field's ball, with coherence and a node
// budget switching on and off, queried of both variants: the allocations they made (expected 0)
// and the points in contact summed; Q is left at the last cycle.
long AllocationsOverASlide(PointshellContactModel& tree, PointshellContactModel& linear, ContactQuery* q,
                           std::int64_t* contacts) {
  const long before = testing::AllocationCount();
  for (int cycle = 0; cycle < 2000; ++cycle) {
    q->cycle = cycle;
    q->node_budget = (cycle / 100) % 2 == 0 ? 0 : 400;
    q->X_WA = Pose::FromTranslation(Eigen::Vector3d(0.1 + 0.004 * std::sin(cycle * 0.01), 0.001, 0));
    *contacts += tree.Evaluate(*q).stats.points_in_contact + linear.Evaluate(*q).stats.points_in_contact;
  }
  return testing::AllocationCount() - before;
}

TEST(PointshellContactModel, EvaluateAllocatesNothing) {
  SlidingPair pair;
  PointshellContactModel& tree = pair.tree;
  PointshellContactModel& linear = pair.linear;
  ContactQuery q;
  std::int64_t contacts = 0;
  EXPECT_EQ(AllocationsOverASlide(tree, linear, &q, &contacts), 0);
  EXPECT_GT(contacts, 0);
}

// Keeping the contacts (KeepContacts, called outside the cycle) leaves Evaluate allocation-free:
// the record goes into the room reserved, for either variant, with coherence and a changing
// node budget, also when more points touch than the room holds.
TEST(PointshellContactModel, EvaluateAllocatesNothingWithContactsKept) {
  SlidingPair pair;
  PointshellContactModel& tree = pair.tree;
  PointshellContactModel& linear = pair.linear;
  ASSERT_TRUE(tree.KeepContacts(1 << 12));
  ASSERT_TRUE(linear.KeepContacts(3));  // fewer than touch: the rest counted
  ContactQuery q;
  std::int64_t contacts = 0;
  EXPECT_EQ(AllocationsOverASlide(tree, linear, &q, &contacts), 0);
  EXPECT_GT(contacts, 0);
  // The last query's lists: as many as touched (the tree's), or the room and the rest counted.
  const ContactResult r_tree = tree.Evaluate(q), r_linear = linear.Evaluate(q);
  ContactList list;
  tree.LatestContacts(&list);
  EXPECT_EQ(list.size(), r_tree.stats.points_in_contact);
  linear.LatestContacts(&list);
  EXPECT_EQ(list.size() + list.not_kept, r_linear.stats.points_in_contact);
}

// States of every point of SHELL in MODEL's latest query Q, asked for in the chunks the model
// accepts.
std::vector<PointState> AllPointStates(ContactModel& model, const ContactQuery& q, const Pointshell& shell) {
  std::vector<std::int32_t> all(std::size_t(shell.num_points()));
  std::iota(all.begin(), all.end(), 0);
  std::vector<PointState> states(all.size());
  for (std::size_t k = 0; k < all.size();) {
    const int n = model.PointStates(q, std::span<const std::int32_t>(all).subspan(k), states.data() + k);
    if (n <= 0) ADD_FAILURE() << "PointStates wrote nothing at point " << k;
    if (n <= 0) break;
    k += std::size_t(n);
  }
  return states;
}

// The per-point states the live view shows (paper Fig. 2) against the field itself: each
// point's d computed directly (double-precision pose, DistanceField::Distance) at the query's
// pose. A point marked in contact has d < 0 and a clear one d >= 0; at full depth without
// coherence every point with d < 0 is reached (the culling test is conservative), so the
// points marked in contact are exactly those with d < 0 and their count is the model's
// points_in_contact. Points within 1e-6 m of the surface are left out (float vs double pose).
TEST(PointshellContactModel, PointStatesAreTheFieldsSignAtTheQueryPose) {
  auto shell = testing::SphereShell(0.05, 48, 4);
  auto field = SphereField(0.06, 0.004);
  std::mt19937 rng(7);
  int culled = 0, clear = 0;
  for (Variant variant : {Variant::kLinear, Variant::kTree}) {
    PointshellContactModel model(variant, shell, field, {});
    for (int trial = 0; trial < 10; ++trial) {
      ContactQuery q;
      q.cycle = trial;
      q.X_WB = RandomPose(rng, 0.02);
      const Eigen::Vector3d dir = Eigen::Vector3d::Random().normalized();
      q.X_WA = {RotationFromVector(Eigen::Vector3d::Random()), q.X_WB.translation + (0.096 + 0.001 * trial) * dir};
      const ContactResult result = model.Evaluate(q);
      const std::vector<PointState> states = AllPointStates(model, q, *shell);
      const Pose X_BA = q.X_WB.Inverse() * q.X_WA;
      int in_contact = 0;
      for (int i = 0; i < shell->num_points(); ++i) {
        const double d = field->Distance(X_BA * Eigen::Vector3d(shell->x[i], shell->y[i], shell->z[i]));
        in_contact += states[i] == PointState::kInContact;
        culled += states[i] == PointState::kNotEvaluated;
        clear += states[i] == PointState::kClear;
        if (std::abs(d) < 1e-6) continue;
        EXPECT_EQ(states[i] == PointState::kInContact, d < 0) << "point " << i << ", d = " << d << ", trial " << trial;
        if (variant == Variant::kLinear) {
          EXPECT_NE(states[i], PointState::kNotEvaluated) << "point " << i;
        }
      }
      EXPECT_EQ(in_contact, result.stats.points_in_contact) << "trial " << trial;
      EXPECT_GT(in_contact, 0) << "trial " << trial;
    }
  }
  EXPECT_GT(culled, 0);  // the tree culled some points, so its states are not all "evaluated"
  EXPECT_GT(clear, 0);
}

// Points below the level rendered are not evaluated, and a model that has not evaluated yet
// marks nothing.
TEST(PointshellContactModel, PointStatesMarkNothingBelowTheLevelRendered) {
  auto shell = testing::SphereShell(0.05, 48, 4);
  auto field = SphereField(0.06, 0.004);
  PointshellContactParams params;
  params.level = 1;
  for (Variant variant : {Variant::kLinear, Variant::kTree}) {
    PointshellContactModel model(variant, shell, field, params);
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.1, 0, 0));
    if (variant == Variant::kTree) {
      const std::vector<PointState> before = AllPointStates(model, q, *shell);
      EXPECT_EQ(std::count(before.begin(), before.end(), PointState::kNotEvaluated), shell->num_points());
    }
    const ContactResult result = model.Evaluate(q);
    const std::vector<PointState> states = AllPointStates(model, q, *shell);
    for (int i = shell->level_point_end[1]; i < shell->num_points(); ++i) EXPECT_EQ(states[i], PointState::kNotEvaluated);
    EXPECT_EQ(std::count(states.begin(), states.end(), PointState::kInContact), result.stats.points_in_contact);
    EXPECT_GT(result.stats.points_in_contact, 0);
  }
}

}  // namespace
}  // namespace contactlab
