// Friction in the paper's model (contact/friction.h) against closed forms: a patch pressed to a
// fixed depth and dragged along the surface holds kappa F_n x while it sticks, reaches mu_s F_n,
// slides at mu_d F_n, unloads elastically when the motion turns back; the same on a curved
// contact; the gradient against finite differences; anchors across graceful degradation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "allocation_counter.h"
#include "contact/test_shells.h"
#include "pointshell_contact/wrench_finite_differences.h"
#include "pointshell_contact/pointshell_contact_model.h"

namespace contactlab {
namespace {

using Variant = PointshellContactModel::Variant;

// Field of the halfspace z < 0 over a slab around the plane: trilinear interpolation
// reproduces d = z exactly, so every depth below is exact to float rounding.
std::shared_ptr<DistanceField> HalfspaceField() {
  return testing::SampleField([](const Eigen::Vector3d& p) { return p.z(); }, Eigen::Vector3d(-0.1, -0.1, -0.03),
                              Eigen::Vector3d(0.1, 0.1, 0.1), 0.01);
}

// A square patch of 20 x 20 points 2 mm apart in the plane z = 0, inward normals +z.
std::shared_ptr<Pointshell> FlatPatch() {
  std::vector<Eigen::Vector3d> p, n;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      p.emplace_back(-0.019 + 0.002 * i, -0.019 + 0.002 * j, 0);
      n.emplace_back(0, 0, 1);
    }
  return testing::MakeNestedShell(p, n, {400});
}

// A sphere of radius 5 cm, 8000 points.
std::shared_ptr<Pointshell> Sphere() {
  std::vector<Eigen::Vector3d> p, n;
  testing::FibonacciSphere(0.05, 8000, 1, &p, &n, false);
  return testing::MakeNestedShell(p, n, {8000});
}

constexpr double kMuS = 0.5, kMuD = 0.3, kKappa = 2000;  // slips after 0.25 mm, slides at 0.15 mm

PointshellContactParams WithFriction(double mu_s = kMuS, double mu_d = kMuD) {
  PointshellContactParams p{.penalty = {.k_C = 300, .L = 0}};
  p.friction = {.mu_static = mu_s, .mu_dynamic = mu_d, .tangential_stiffness = kKappa};
  return p;
}

// A at START pressed into the halfspace and moved along x by each of the offsets, one query each.
struct Drag {
  std::vector<double> x, tangential, normal;
  std::vector<int> sliding;
};
Drag DragAlong(PointshellContactModel& model, const Eigen::Vector3d& start, const std::vector<double>& offsets) {
  Drag d;
  std::int64_t cycle = 0;
  for (double x : offsets) {
    ContactQuery q;
    q.cycle = cycle++;
    q.X_WA = Pose::FromTranslation(start + Eigen::Vector3d(x, 0, 0));
    const ContactResult r = model.Evaluate(q);
    d.x.push_back(x);
    d.tangential.push_back(r.on_B.force.x());
    d.normal.push_back(-r.on_B.force.z());
    d.sliding.push_back(r.stats.contacts_sliding);
  }
  return d;
}

// 0 -> 1 mm -> 0.2 mm in 1 µm steps.
std::vector<double> ThereAndBack() {
  std::vector<double> x;
  for (int i = 0; i <= 1000; ++i) x.push_back(1e-6 * i);
  for (int i = 999; i >= 200; --i) x.push_back(1e-6 * i);
  return x;
}

// The closed form of a contact dragged along the surface and back: F_t = kappa F_n x up to
// mu_s F_n, then mu_d F_n; coming back it unloads with the same slope to -mu_s F_n and slides
// at -mu_d F_n. Checks DRAG (at normal force F_N) against it within REL, and that the normal
// force stays within NORMAL_REL of F_N (on a curved A each contact's friction lies in its own
// tangent plane, so some of it is normal to the plane).
void ExpectCoulombHysteresis(const Drag& drag, double F_n, double rel, double normal_rel) {
  double peak = 0;
  std::size_t i = 0;
  for (; i < drag.x.size() && drag.x[i] < 0.9 * kMuS / kKappa; ++i) {  // sticking: elastic
    EXPECT_NEAR(drag.tangential[i], kKappa * F_n * drag.x[i], rel * kMuS * F_n) << "at x " << drag.x[i];
    EXPECT_EQ(drag.sliding[i], 0) << "at x " << drag.x[i];
  }
  for (std::size_t k = 0; k < drag.x.size(); ++k) peak = std::max(peak, drag.tangential[k]);
  EXPECT_NEAR(peak, kMuS * F_n, 0.02 * kMuS * F_n) << "the static limit mu_s F_n";
  // Sliding forward, past 0.4 mm: mu_d F_n, every contact sliding.
  const std::size_t turn = 1000;
  for (std::size_t k = 400; k <= turn; ++k) {
    EXPECT_NEAR(drag.tangential[k], kMuD * F_n, 0.02 * kMuD * F_n) << "at x " << drag.x[k];
    EXPECT_GT(drag.sliding[k], 0);
  }
  // Back: elastic unloading with the sticking slope for (mu_d + mu_s) / kappa = 0.4 mm.
  for (std::size_t k = turn + 1; k < turn + 350; ++k) {
    const double back = drag.x[turn] - drag.x[k];
    EXPECT_NEAR(drag.tangential[k], kMuD * F_n - kKappa * F_n * back, rel * kMuS * F_n) << "back by " << back;
    EXPECT_EQ(drag.sliding[k], 0) << "back by " << back;
  }
  double low = 0;
  for (std::size_t k = turn; k < drag.x.size(); ++k) low = std::min(low, drag.tangential[k]);
  EXPECT_NEAR(low, -kMuS * F_n, 0.02 * kMuS * F_n);
  EXPECT_NEAR(drag.tangential.back(), -kMuD * F_n, 0.02 * kMuD * F_n) << "sliding back";
  for (double n : drag.normal) EXPECT_NEAR(n, F_n, normal_rel * F_n);
}

TEST(Friction, FlatPatchSticksSlipsAtTheStaticLimitAndSlidesAtTheDynamicOne) {
  auto shell = FlatPatch();
  auto field = HalfspaceField();
  PointshellContactModel model(Variant::kLinear, shell, field, WithFriction());
  const double F_n = 400 * 300 * 5e-4;  // 400 points 0.5 mm deep: 60 N
  const Drag drag = DragAlong(model, Eigen::Vector3d(0, 0, -5e-4), ThereAndBack());
  ExpectCoulombHysteresis(drag, F_n, 0.01, 1e-5);
  double peak = 0;
  for (double t : drag.tangential) peak = std::max(peak, t);
  std::printf("flat: F_n %.4f N, peak %.5f N (mu_s F_n %.5f, error %.4f %%), slide %.5f N (mu_d F_n %.5f)\n", F_n,
              peak, kMuS * F_n, 100 * (peak / (kMuS * F_n) - 1), drag.tangential[900], kMuD * F_n);
}

TEST(Friction, CurvedContactReachesTheStaticLimitOfItsWholeNormalForce) {
  // A sphere 2 mm into the plane: depths from 0 to 2 mm, each contact with its own F_n, and
  // the law's stiffness proportional to the load makes them all slip at one travel.
  auto shell = Sphere();
  auto field = HalfspaceField();
  PointshellContactModel frictionless(Variant::kLinear, shell, field, {.penalty = {.k_C = 300, .L = 0}});
  const Eigen::Vector3d start(0.001, -0.002, 0.05 - 0.002);
  ContactQuery q;
  q.X_WA = Pose::FromTranslation(start);
  const ContactResult r0 = frictionless.Evaluate(q);
  const double F_n = -r0.on_B.force.z();
  ASSERT_GT(r0.stats.points_in_contact, 100);
  PointshellContactModel model(Variant::kLinear, shell, field, WithFriction());
  const Drag drag = DragAlong(model, start, ThereAndBack());
  // The contact set of a sphere on a plane moves with the sphere, so F_n holds throughout.
  ExpectCoulombHysteresis(drag, F_n, 0.01, 2e-3);
  double peak = 0;
  for (double t : drag.tangential) peak = std::max(peak, t);
  std::printf("curved: %d contacts, F_n %.4f N, peak %.5f N (error %.4f %%), slide %.5f N (error %.4f %%)\n",
              r0.stats.points_in_contact, F_n, peak, 100 * (peak / (kMuS * F_n) - 1), drag.tangential[900],
              100 * (drag.tangential[900] / (kMuD * F_n) - 1));
}

TEST(Friction, TheTorqueOfASlidingPatchIsItsForceAtTheContactPoints) {
  // The patch slides at mu_d: each contact's friction force acts at its point, so the torque
  // about B's origin is sum p x f, here with p in the plane z = -0.5 mm and f along x.
  auto shell = FlatPatch();
  auto field = HalfspaceField();
  PointshellContactModel model(Variant::kLinear, shell, field, WithFriction());
  const Eigen::Vector3d start(0.01, 0.02, -5e-4);
  Drag drag;
  ContactResult r;
  for (int i = 0; i <= 600; ++i) {
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(start + Eigen::Vector3d(1e-6 * i, 0, 0));
    r = model.Evaluate(q);
  }
  // Normal force -F_n z at the patch's centre c (0.0106, 0.02): torque c x (-F_n z); friction
  // mu_d F_n x at height z = -0.5 mm: torque (0, z mu_d F_n, -c_y mu_d F_n).
  const double F_n = 60, F_t = kMuD * F_n, cx = 0.01 + 6e-4, cy = 0.02, z = -5e-4;
  const Eigen::Vector3d expected = Eigen::Vector3d(cx, cy, z).cross(Eigen::Vector3d(0, 0, -F_n)) +
                                   Eigen::Vector3d(cx, cy, z).cross(Eigen::Vector3d(F_t, 0, 0));
  EXPECT_LT((r.on_B.torque - expected).norm(), 1e-3 * F_n * 0.02) << r.on_B.torque.transpose() << " vs "
                                                                   << expected.transpose();
}

using testing::FiniteDifferenceGradient;

// Loads MODEL's anchors: A pressed at X_WA0 (B at X_WB), then moved by SHIFT while it sticks.
ContactQuery StickAndShift(PointshellContactModel& model, const Pose& X_WB, const Pose& X_WA0,
                           const Eigen::Vector3d& shift) {
  ContactQuery q;
  q.X_WB = X_WB;
  q.X_WA = X_WA0;
  model.Evaluate(q);
  q.X_WA.translation += shift;
  return q;
}

TEST(Friction, StickingGradientMatchesFiniteDifferencesOfTheWrench) {
  // The flat patch under the halfspace rule (exact there) and the sphere under the field's own
  // gradient, each loaded tangentially to 40 % of its slip travel so that no perturbation slips.
  struct Case {
    const char* name;
    std::shared_ptr<Pointshell> shell;
    ContactGradient gradient;
    Pose X_WB, X_WA;
  };
  const Pose X_WB{RotationFromVector(Eigen::Vector3d(0, 0, 0.3)), Eigen::Vector3d(0.003, -0.001, 0.002)};
  const Case cases[] = {
      {"flat patch, halfspace rule", FlatPatch(), ContactGradient::kHalfspace, X_WB,
       Pose::FromTranslation(Eigen::Vector3d(0.004, 0.002, 0.0015))},
      {"sphere, field gradient", Sphere(), ContactGradient::kField,
       Pose{RotationFromVector(Eigen::Vector3d(0.2, -0.1, 0.05)), Eigen::Vector3d(0.003, -0.001, 0.002)},
       Pose::FromTranslation(Eigen::Vector3d(0.004, 0.002, 0.05))},
  };
  auto field = HalfspaceField();
  for (const Case& c : cases) {
    PointshellContactParams params = WithFriction();
    params.gradient = c.gradient;
    PointshellContactModel model(Variant::kLinear, c.shell, field, params);
    PointshellContactModel frictionless(Variant::kLinear, c.shell, field,
                                        {.penalty = params.penalty, .gradient = c.gradient});
    const ContactQuery q = StickAndShift(model, c.X_WB, c.X_WA, Eigen::Vector3d(0.4 * kMuS / kKappa, 0, 0));
    const ContactResult r = model.Evaluate(q);
    ASSERT_GT(r.stats.points_in_contact, 20) << c.name;
    ASSERT_EQ(r.stats.contacts_sliding, 0) << c.name;
    const Matrix6d fd = FiniteDifferenceGradient(model, q, 1e-6);
    const Matrix6d friction_part = r.K_B - frictionless.Evaluate(q).K_B;
    EXPECT_LT((r.K_B - fd).norm(), 5e-3 * fd.norm()) << c.name << "\nanalytic\n" << r.K_B << "\nfd\n" << fd;
    // Friction's own part is no rounding error: sticking adds stiffness along the surface.
    EXPECT_GT(friction_part.norm(), 0.2 * fd.norm()) << c.name;
    ASSERT_EQ(model.Evaluate(q).stats.contacts_sliding, 0) << c.name << ": the differences let it slip";
  }
}

TEST(Friction, TangentialStiffnessOfSticksKeepsTheGradientSymmetricInTranslation) {
  // Pure translation of B against a sticking flat patch: dF_t/dx = -kappa F_n (I - N N^T) on the
  // tangent plane, the closed form of a linear spring of stiffness kappa F_n.
  auto shell = FlatPatch();
  auto field = HalfspaceField();
  PointshellContactModel model(Variant::kLinear, shell, field, WithFriction());
  const ContactQuery q = StickAndShift(model, Pose(), Pose::FromTranslation(Eigen::Vector3d(0, 0, -5e-4)),
                                       Eigen::Vector3d::Zero());
  const ContactResult r = model.Evaluate(q);
  const double F_n = 60;
  EXPECT_NEAR(r.K_B(0, 0), -kKappa * F_n, 1e-5 * kKappa * F_n);  // depths in float
  EXPECT_NEAR(r.K_B(1, 1), -kKappa * F_n, 1e-5 * kKappa * F_n);
  EXPECT_NEAR(r.K_B(0, 1), 0, 1e-9 * kKappa * F_n);
}

TEST(Friction, RoleReversalGivesEqualAndOppositeFriction) {
  // Two spheres overlapping by 4 mm along x; A slides along y. Sphere a as the pointshell in b's
  // field, then b as the pointshell in a's: the friction on each body agrees within the
  // resolution of the two discretisations.
  const double Ra = 0.04, Rb = 0.06, h = 0.0015;
  auto sphere_field = [h](double R) {
    return testing::SampleField([R](const Eigen::Vector3d& p) { return p.norm() - R; },
                                Eigen::Vector3d::Constant(-1.3 * R), Eigen::Vector3d::Constant(1.3 * R), h);
  };
  std::vector<Eigen::Vector3d> p, n;
  testing::FibonacciSphere(Ra, 16000, 2, &p, &n, false);
  auto sa = testing::MakeNestedShell(p, n, {16000});
  p.clear(), n.clear();
  testing::FibonacciSphere(Rb, 36000, 3, &p, &n, false);
  auto sb = testing::MakeNestedShell(p, n, {36000});
  PointshellContactParams params = WithFriction();
  params.penalty = {.k_C = 800, .L = 10};
  PointshellContactModel ab(Variant::kLinear, sa, sphere_field(Rb), params);
  PointshellContactModel ba(Variant::kLinear, sb, sphere_field(Ra), params);
  const double gap = Ra + Rb - 0.004;
  double ab_peak = 0, ba_peak = 0, ab_slide = 0, ba_slide = 0, ab_normal = 0, ba_normal = 0;
  for (int i = 0; i <= 800; ++i) {
    const Eigen::Vector3d offset(gap, 1e-6 * i, 0);
    ContactQuery q1, q2;
    q1.X_WA = Pose::FromTranslation(offset);  // a moves: force on b
    q2.X_WB = Pose::FromTranslation(offset);  // a (now the field body) moves: force on a
    const ContactResult r1 = ab.Evaluate(q1), r2 = ba.Evaluate(q2);
    const double on_b_1 = r1.on_B.force.y(), on_b_2 = -r2.on_B.force.y();
    ab_peak = std::max(ab_peak, on_b_1), ba_peak = std::max(ba_peak, on_b_2);
    ab_slide = on_b_1, ba_slide = on_b_2;
    ab_normal = r1.on_B.force.x(), ba_normal = -r2.on_B.force.x();
  }
  std::printf("roles a-in-b / b-in-a: normal %.4f / %.4f N, peak %.4f / %.4f N, slide %.4f / %.4f N\n", ab_normal,
              ba_normal, ab_peak, ba_peak, ab_slide, ba_slide);
  ASSERT_GT(ab_peak, 0);
  EXPECT_GT(ba_peak, 0) << "friction on b points along a's motion in both roles";
  EXPECT_NEAR(ba_peak / ab_peak, 1, 0.02);
  EXPECT_NEAR(ba_slide / ab_slide, 1, 0.02);
  // Each contact slides in its own tangent plane, and the normals of a patch between two spheres
  // fan out, so the force along the motion falls a little short of mu_d F_n.
  EXPECT_NEAR(ab_slide, kMuD * std::abs(ab_normal), 0.05 * kMuD * std::abs(ab_normal));
  EXPECT_NEAR(ba_slide, kMuD * std::abs(ba_normal), 0.05 * kMuD * std::abs(ba_normal));
}

TEST(Friction, AnchorsPassToTheChildrenWhenTheLevelDeepens) {
  // A tree of two levels (100, then 400 points of the flat patch). Loaded while a node budget
  // keeps the model at level 0, then given the whole tree: the points of level 1 take over
  // their parents' displacement, so the friction per newton of normal force is unchanged.
  std::vector<Eigen::Vector3d> p, n;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      p.emplace_back(-0.019 + 0.002 * i, -0.019 + 0.002 * j, 0);
      n.emplace_back(0, 0, 1);
    }
  // Level 0: every other point in each direction, first in the list.
  std::vector<Eigen::Vector3d> ordered_p, ordered_n;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < 20; ++i)
      for (int j = 0; j < 20; ++j) {
        const bool coarse = i % 2 == 0 && j % 2 == 0;
        if (coarse == (pass == 0)) ordered_p.push_back(p[std::size_t(20 * i + j)]), ordered_n.push_back(n[0]);
      }
  auto shell = testing::MakeNestedShell(ordered_p, ordered_n, {100, 400});
  auto field = HalfspaceField();
  for (bool inherit : {true, false}) {
    PointshellContactModel model(Variant::kTree, shell, field, WithFriction());
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0, 0, -5e-4));
    q.node_budget = 100;  // level 0 only
    ContactResult r = model.Evaluate(q);
    ASSERT_EQ(r.stats.level_rendered, 0);
    q.X_WA.translation.x() += 1e-4;  // 40 % of the slip travel
    q.cycle = 1;
    r = model.Evaluate(q);
    const double ratio_coarse = r.on_B.force.x() / -r.on_B.force.z();
    EXPECT_NEAR(ratio_coarse, kKappa * 1e-4, 1e-3);
    if (!inherit) model.Reset();  // the contrast: fresh anchors everywhere
    q.node_budget = 0;
    q.cycle = 2;
    r = model.Evaluate(q);
    ASSERT_EQ(r.stats.level_rendered, 1);
    const double ratio_fine = r.on_B.force.x() / -r.on_B.force.z();
    if (inherit) {
      EXPECT_NEAR(ratio_fine, ratio_coarse, 1e-3 * ratio_coarse) << "the level-1 points start where their parents are";
    } else {
      EXPECT_NEAR(ratio_fine, 0, 1e-9) << "after Reset no contact has travelled";
    }
  }
}

TEST(Friction, CoherenceResetKeepsTheAnchorsAndResetForgetsThem) {
  auto shell = FlatPatch();
  auto field = HalfspaceField();
  PointshellContactModel model(Variant::kLinear, shell, field, WithFriction());
  ContactQuery q = StickAndShift(model, Pose(), Pose::FromTranslation(Eigen::Vector3d(0, 0, -5e-4)),
                                 Eigen::Vector3d(1e-4, 0, 0));
  const double loaded = model.Evaluate(q).on_B.force.x();
  EXPECT_NEAR(loaded, kKappa * 60 * 1e-4, 1e-3 * loaded);
  model.ResetCoherence();
  EXPECT_NEAR(model.Evaluate(q).on_B.force.x(), loaded, 1e-9 * loaded);
  model.Reset();
  EXPECT_NEAR(model.Evaluate(q).on_B.force.x(), 0, 1e-12);
}

TEST(Friction, ContactsListTheirFrictionAndWhetherTheyStick) {
  auto shell = FlatPatch();
  auto field = HalfspaceField();
  PointshellContactModel model(Variant::kLinear, shell, field, WithFriction());
  ASSERT_TRUE(model.KeepContacts(1000));
  ContactList list;
  for (const double shift : {1e-4, 6e-4}) {  // sticking, then sliding
    model.Reset();
    ContactQuery q = StickAndShift(model, Pose(), Pose::FromTranslation(Eigen::Vector3d(0, 0, -5e-4)),
                                   Eigen::Vector3d(shift, 0, 0));
    const ContactResult r = model.Evaluate(q);
    model.LatestContacts(&list);
    ASSERT_EQ(list.size(), 400);
    ASSERT_EQ(list.tangential.size(), 400u);
    ASSERT_EQ(list.sticking.size(), 400u);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& t : list.tangential) sum += t;
    EXPECT_LT((sum - Eigen::Vector3d(r.on_B.force.x(), r.on_B.force.y(), 0)).norm(), 1e-6 * 60);  // summed in float
    const bool sticks = shift < kMuS / kKappa;
    for (std::uint8_t s : list.sticking) EXPECT_EQ(s, sticks ? 1 : 0);
    EXPECT_EQ(r.stats.contacts_sliding, sticks ? 0 : 400);
  }
}

TEST(Friction, ExtremeCoefficientsKeepTheWrenchFinite) {
  // The block's bounds: coefficients up to 10, stiffness up to 1e9, a dynamic coefficient as
  // small as a double allows. Sticking and sliding, the wrench and K_B stay finite, and a rim
  // below a picometre slides without friction.
  auto shell = FlatPatch();
  auto field = HalfspaceField();
  for (const double mu_d : {1e-300, 1e-20, 1e-9, 10.0}) {
    for (const double kappa : {1e-300, 1.0, 1e9}) {
      PointshellContactParams params = WithFriction(10, mu_d);
      params.friction.tangential_stiffness = kappa;
      PointshellContactModel model(Variant::kLinear, shell, field, params);
      ContactResult r;
      for (int i = 0; i <= 20; ++i) {
        ContactQuery q;
        q.X_WA = Pose::FromTranslation(Eigen::Vector3d(1e-5 * i, 0, -5e-4));
        r = model.Evaluate(q);
        ASSERT_TRUE(r.on_B.force.allFinite() && r.on_B.torque.allFinite() && r.K_B.allFinite())
            << "mu_d " << mu_d << " kappa " << kappa << " step " << i;
      }
      if (mu_d / kappa < FrictionParams::kSmallestRim && r.stats.contacts_sliding > 0) {
        EXPECT_NEAR(r.on_B.force.x(), 0, 1e-9) << "mu_d " << mu_d << " kappa " << kappa;
      }
    }
  }
}

TEST(Friction, EvaluateAllocatesNothingWithFriction) {
  auto shell = testing::SphereShell(0.05, 48, 4);
  auto field = HalfspaceField();
  PointshellContactModel tree(Variant::kTree, shell, field, WithFriction());
  ASSERT_TRUE(tree.KeepContacts(1 << 12));
  std::int64_t allocations = 0, contacts = 0;
  ContactQuery q;
  for (int i = 0; i < 200; ++i) {
    q.cycle = i;
    q.node_budget = i % 3 == 0 ? 40 : 0;  // degrading and deepening
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(1e-5 * i, 0, 0.05 - 0.002));
    const long before = testing::AllocationCount();
    const ContactResult r = tree.Evaluate(q);
    allocations += testing::AllocationCount() - before;
    contacts += r.stats.points_in_contact;
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(contacts, 0);
}

}  // namespace
}  // namespace contactlab
