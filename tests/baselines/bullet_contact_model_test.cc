// Tests of the Bullet baseline (baselines/bullet): wrench sign (Bullet's m_normalWorldOnB points from B to A),
// torque about B's origin, zero wrench when apart, K_B against finite differences; its settings
// (bullet_params.h): the convex hull's depth of a tessellated ball pressed into a box against
// the closed form, with and without the margins, the convex decomposition of a convex body,
// and bad values refused by key.
#include "baselines/bullet/bullet_contact_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "scene/scene.h"
#include "penalty_model_checks.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::unique_ptr<ContactModel> MakeBulletWith(std::shared_ptr<const TriangleMesh> A,
                                             std::shared_ptr<const TriangleMesh> B, double k_C, int L,
                                             BulletContactParams p) {
  p.penalty.k_C = k_C;
  p.penalty.L = L;
  return std::make_unique<BulletContactModel>(std::move(A), std::move(B), p);
}

std::unique_ptr<ContactModel> MakeBullet(std::shared_ptr<const TriangleMesh> A, std::shared_ptr<const TriangleMesh> B,
                                      double k_C, int L) {
  return MakeBulletWith(std::move(A), std::move(B), k_C, L, BulletContactParams{});
}

// The default parameters with SHAPE, MARGIN and SUBTRACT.
BulletContactParams Settings(BulletShape shape, double margin = BulletOwnParams().margin, bool subtract = true) {
  BulletContactParams p;
  p.own = {.margin = margin, .subtract_margins = subtract, .shape = shape};
  return p;
}

std::unique_ptr<ContactModel> MakeBulletHull(std::shared_ptr<const TriangleMesh> A,
                                             std::shared_ptr<const TriangleMesh> B, double k_C, int L) {
  return MakeBulletWith(std::move(A), std::move(B), k_C, L, Settings(BulletShape::kConvexHull));
}

std::unique_ptr<ContactModel> MakeBulletPieces(std::shared_ptr<const TriangleMesh> A,
                                               std::shared_ptr<const TriangleMesh> B, double k_C, int L) {
  return MakeBulletWith(std::move(A), std::move(B), k_C, L,
                        Settings(BulletShape::kConvexDecomposition));
}

// A ball of radius r tessellated with its vertices on the sphere, pressed d into the top face
// of a box, both turned so nothing is axis-aligned.
struct BallInBox {
  double r = 0.02;
  std::shared_ptr<const TriangleMesh> ball = std::make_shared<TriangleMesh>(MakeSphere(r, 3));
  std::shared_ptr<const TriangleMesh> box = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(0.06, 0.05, 0.02)));
  // r minus the distance of the ball's closest face plane to its centre: how much shallower
  // than d its hull may reach.
  double Flattening() const {
    double closest = r;
    for (const Eigen::Vector3i& t : ball->triangles) {
      const Eigen::Vector3d &a = ball->vertices[t[0]], &b = ball->vertices[t[1]], &c = ball->vertices[t[2]];
      closest = std::min(closest, std::abs((b - a).cross(c - a).normalized().dot(a)));
    }
    return r - closest;
  }
  ContactQuery Query(double d) const {
    ContactQuery q;
    q.X_WB.translation = Eigen::Vector3d(0.01, -0.02, 0.03);
    q.X_WB.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
    q.X_WA.translation = q.X_WB * Eigen::Vector3d(0.007, -0.004, 0.02 + r - d);
    q.X_WA.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(2, -1, 1).normalized()));
    return q;
  }
};

TEST(BulletContactModel, ForceOnBPointsAwayFromA) { testing::ExpectForceOnBPointsAwayFromA(MakeBullet); }
TEST(BulletContactModel, TorqueIsAboutBsOrigin) { testing::ExpectTorqueAboutBsOrigin(MakeBullet); }
TEST(BulletContactModel, ZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeBullet); }
TEST(BulletContactModel, TranslationGradientMatchesFiniteDifferences) {
  testing::ExpectTranslationGradientMatchesFiniteDifferences(MakeBullet);
}

TEST(BulletContactModel, ConvexHullForceOnBPointsAwayFromA) { testing::ExpectForceOnBPointsAwayFromA(MakeBulletHull); }
// (No torque check for the convex hull: a face-on-face contact is one GJK/EPA point somewhere
// in the overlap, and it moves when B's mesh is shifted in its own frame — on BoxOnBox the
// torque about the shifted origin is 0.08 N m off the moved one. The force is checked.)
TEST(BulletContactModel, ConvexHullZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeBulletHull); }
TEST(BulletContactModel, ConvexDecompositionForceOnBPointsAwayFromA) {
  testing::ExpectForceOnBPointsAwayFromA(MakeBulletPieces);
}
TEST(BulletContactModel, ConvexDecompositionZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeBulletPieces); }

// The hulls of the ball and the box overlap by d less the ball's flattening e (BallInBox): one
// GJK/EPA point, so the force on B is k_C δ along -z_B, δ within e of d with the margins
// subtracted and of d + 2 margin without, for two margins.
TEST(BulletContactModel, ConvexHullDepthOfABallInABoxIsTheClosedForm) {
  const BallInBox s;
  const double k_C = 2000, e = s.Flattening();
  ASSERT_LT(e, 0.02 * s.r);
  for (const double margin : {0.0, 0.0005, 0.002}) {
    for (const bool subtract : {true, false}) {
      for (const double d : {0.0005, 0.002, 0.005}) {
        const BulletContactParams p = Settings(BulletShape::kConvexHull, margin, subtract);
        const ContactQuery q = s.Query(d);
        const ContactResult res = MakeBulletWith(s.ball, s.box, k_C, 10, p)->Evaluate(q);
        const std::string what = "margin " + std::to_string(margin) + (subtract ? ", subtracted" : "") + ", d " +
                                 std::to_string(d);
        ASSERT_EQ(res.stats.points_in_contact, 1) << what;
        const double expected = subtract ? d : d + 2 * margin;
        EXPECT_NEAR(res.stats.max_penetration, expected, e + 1e-6) << what;
        const Eigen::Vector3d z_B = q.X_WB.R().col(2);
        EXPECT_NEAR(res.on_B.force.dot(-z_B), k_C * res.stats.max_penetration, 1e-3 * k_C * expected) << what;
        EXPECT_LT((res.on_B.force + res.on_B.force.norm() * z_B).norm(), 0.01 * res.on_B.force.norm()) << what;
      }
    }
  }
}

// A convex body decomposes into convex pieces that fill it: a box pressed d into a wider box
// pushes B straight down with every point at most d deep (each piece's depth is its overlap
// with the box, not more).
TEST(BulletContactModel, ConvexDecompositionOfABoxPressesLikeTheBox) {
  testing::BoxOnBox s;
  for (const double d : {0.001, 0.003}) {
    const ContactQuery q = s.Query(d);
    const ContactResult r = MakeBulletPieces(s.A, s.B, 2000, 10)->Evaluate(q);
    ASSERT_GT(r.stats.points_in_contact, 0) << "d " << d;
    EXPECT_NEAR(r.stats.max_penetration, d, 0.05 * d) << "d " << d;
    const Eigen::Vector3d z_B = q.X_WB.R().col(2);
    EXPECT_GT(-r.on_B.force.dot(z_B), 0.99 * r.on_B.force.norm()) << "d " << d;
  }
}

// Each bad value of the settings is refused when the scene is read, naming the key.
TEST(BulletContactModel, BadSettingsAreRefusedNamingTheKey) {
  testing::ExpectModelKeysRefused({
      {"bullet_margin: -0.001", "s.yaml:5: model.bullet_margin: must be in [0, 0.01], got -0.001"},
      {"bullet_margin: 0.5", "model.bullet_margin: must be in [0, 0.01], got 0.5"},
      {"bullet_subtract_margins: maybe", "bullet_subtract_margins"},
      {"bullet_shape: sphere", "model.bullet_shape: 'sphere' is not one of: gimpact, convex-hull, convex-decomposition"},
  }, "bullet_margin: 0.0001, bullet_subtract_margins: false, bullet_shape: convex-hull");
  testing::BoxOnBox s;
  try {
    MakeBulletWith(s.A, s.B, 2000, 10, Settings(BulletShape::kGImpact, -1e-3));
    ADD_FAILURE() << "a negative margin was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bullet_margin"), std::string::npos) << e.what();
  }
}

TEST(BulletContactModel, RejectsEmptyMeshAndNegativeStiffness) {
  testing::BoxOnBox s;
  EXPECT_THROW(MakeBullet(std::make_shared<TriangleMesh>(), s.B, 1000, 10), Error);
  EXPECT_THROW(MakeBullet(s.A, s.B, -1, 10), Error);
}

}  // namespace
}  // namespace contactlab
