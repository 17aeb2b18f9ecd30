// Tests of the FCL baseline (baselines/fcl): wrench sign (FCL's normal from object 1 to 2),
// torque about B's origin, zero wrench when apart, K_B against finite differences; its settings
// (fcl_params.h): every bounding volume gives OBBRSS's contacts, the convex shapes' depth of a
// tessellated ball pressed into a box against the closed form, bad values refused by key.
#include "baselines/fcl/fcl_contact_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene.h"
#include "penalty_model_checks.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {
namespace {

// The default parameters with BV, SHAPE and MAX_CONTACTS.
FclContactParams Settings(FclBv bv, FclShape shape = FclShape::kMesh,
                          long long max_contacts = FclOwnParams().max_contacts) {
  FclContactParams p;
  p.own = {.bv = bv, .max_contacts = max_contacts, .shape = shape};
  return p;
}

std::unique_ptr<ContactModel> MakeFclWith(std::shared_ptr<const TriangleMesh> A, std::shared_ptr<const TriangleMesh> B,
                                          double k_C, int L, FclContactParams p) {
  p.penalty.k_C = k_C;
  p.penalty.L = L;
  return std::make_unique<FclContactModel>(std::move(A), std::move(B), p);
}

std::unique_ptr<ContactModel> MakeFcl(std::shared_ptr<const TriangleMesh> A, std::shared_ptr<const TriangleMesh> B,
                                      double k_C, int L) {
  return MakeFclWith(std::move(A), std::move(B), k_C, L, FclContactParams{});
}

std::unique_ptr<ContactModel> MakeFclConvex(std::shared_ptr<const TriangleMesh> A,
                                            std::shared_ptr<const TriangleMesh> B, double k_C, int L) {
  return MakeFclWith(std::move(A), std::move(B), k_C, L, Settings(FclBv::kObbrss, FclShape::kConvex));
}

TEST(FclContactModel, ForceOnBPointsAwayFromA) { testing::ExpectForceOnBPointsAwayFromA(MakeFcl); }
TEST(FclContactModel, TorqueIsAboutBsOrigin) { testing::ExpectTorqueAboutBsOrigin(MakeFcl); }
TEST(FclContactModel, ZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeFcl); }
TEST(FclContactModel, TranslationGradientMatchesFiniteDifferences) {
  testing::ExpectTranslationGradientMatchesFiniteDifferences(MakeFcl);
}

// The bounding volume only decides which triangle pairs are culled, never which pairs
// intersect: every type gives OBBRSS's contacts (count, force and torque to rounding), on a
// flat box-on-box contact and on a ball pressed into a box's face.
TEST(FclContactModel, EveryBoundingVolumeGivesTheContactsOfObbrss) {
  testing::BoxOnBox s;
  auto ball = std::make_shared<TriangleMesh>(MakeSphere(0.02, 2));
  struct Case {
    std::shared_ptr<const TriangleMesh> A;
    ContactQuery q;
  };
  ContactQuery q_ball = s.Query(0);
  q_ball.X_WA.translation = q_ball.X_WB * Eigen::Vector3d(0.004, -0.003, 0.05 + 0.02 - 0.002);
  const Case cases[] = {{s.A, s.Query(0.001)}, {s.A, s.Query(0.003)}, {ball, q_ball}};
  const FclBv all[] = {FclBv::kObb, FclBv::kKios};
  for (const Case& c : cases) {
    const ContactResult ref = MakeFcl(c.A, s.B, 2000, 10)->Evaluate(c.q);
    ASSERT_GT(ref.stats.points_in_contact, 0);
    const double f = ref.on_B.force.norm();
    for (const FclBv bv : all) {
      const ContactResult r = MakeFclWith(c.A, s.B, 2000, 10, Settings(bv))->Evaluate(c.q);
      EXPECT_EQ(r.stats.points_in_contact, ref.stats.points_in_contact) << FclBvName(bv);
      EXPECT_LT((r.on_B.force - ref.on_B.force).norm(), 1e-9 * f) << FclBvName(bv);
      EXPECT_LT((r.on_B.torque - ref.on_B.torque).norm(), 1e-9 * f) << FclBvName(bv);
      EXPECT_NEAR(r.stats.max_penetration, ref.stats.max_penetration, 1e-12) << FclBvName(bv);
    }
  }
}

TEST(FclContactModel, ConvexForceOnBPointsAwayFromA) { testing::ExpectForceOnBPointsAwayFromA(MakeFclConvex); }
TEST(FclContactModel, ConvexTorqueIsAboutBsOrigin) { testing::ExpectTorqueAboutBsOrigin(MakeFclConvex); }
TEST(FclContactModel, ConvexZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeFclConvex); }

// A tessellated ball of radius r (vertices on the sphere) pressed d into a box's top face, both
// turned so nothing is axis-aligned: the hulls overlap by d less the ball's flattening toward
// the face, at most r minus the distance of its closest face plane to its centre (e). One
// contact, so the force on B is k_C δ along -z_B with δ within e of d.
TEST(FclContactModel, ConvexDepthOfABallInABoxIsTheClosedForm) {
  const double r = 0.02, k_C = 2000;
  auto ball = std::make_shared<TriangleMesh>(MakeSphere(r, 3));
  auto box = std::make_shared<TriangleMesh>(MakeBox(Eigen::Vector3d(0.06, 0.05, 0.02)));
  double closest_face = r;
  for (const Eigen::Vector3i& t : ball->triangles) {
    const Eigen::Vector3d &a = ball->vertices[t[0]], &b = ball->vertices[t[1]], &c = ball->vertices[t[2]];
    closest_face = std::min(closest_face, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  const double e = r - closest_face;
  ASSERT_LT(e, 0.02 * r);
  {
    for (const double d : {0.0005, 0.002, 0.005}) {
      ContactQuery q;
      q.X_WB.translation = Eigen::Vector3d(0.01, -0.02, 0.03);
      q.X_WB.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
      q.X_WA.translation = q.X_WB * Eigen::Vector3d(0.007, -0.004, 0.02 + r - d);
      q.X_WA.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(-0.7, Eigen::Vector3d(2, -1, 1).normalized()));
      const ContactResult res =
          MakeFclWith(ball, box, k_C, 10, Settings(FclBv::kObbrss, FclShape::kConvex))->Evaluate(q);
      const std::string what = "d " + std::to_string(d);
      ASSERT_EQ(res.stats.points_in_contact, 1) << what;
      EXPECT_NEAR(res.stats.max_penetration, d, e + 1e-6 * d) << what;
      const Eigen::Vector3d z_B = q.X_WB.R().col(2);
      EXPECT_NEAR(res.on_B.force.dot(-z_B), k_C * res.stats.max_penetration, 1e-9 * k_C) << what;
      EXPECT_LT((res.on_B.force + res.on_B.force.norm() * z_B).norm(), 1e-3 * res.on_B.force.norm()) << what;
    }
  }
}

// Each bad value of the settings is refused when the scene is read, naming the key.
TEST(FclContactModel, BadSettingsAreRefusedNamingTheKey) {
  testing::ExpectModelKeysRefused({
      {"fcl_max_contacts: 0", "s.yaml:5: model.fcl_max_contacts: must be between 1 and 100000000, got 0"},
      {"fcl_max_contacts: -5", "model.fcl_max_contacts: must be between 1 and"},
      {"fcl_bv: sphere", "model.fcl_bv: 'sphere' is not one of: obbrss, obb, kios"},
      {"fcl_shape: hull", "model.fcl_shape: 'hull' is not one of: mesh, convex"},
      {"fcl_gjk: indep", "fcl_gjk"},
      {"fcl_bv: rss", "'rss' is not one of: obbrss, obb, kios"},
  }, "fcl_bv: kios, fcl_max_contacts: 64, fcl_shape: convex");
  testing::BoxOnBox s;
  EXPECT_THROW(MakeFclWith(s.A, s.B, 2000, 10, Settings(FclBv::kObbrss, FclShape::kMesh, 0)), Error);
}

TEST(FclContactModel, RejectsEmptyMeshAndNegativeStiffness) {
  testing::BoxOnBox s;
  EXPECT_THROW(MakeFcl(std::make_shared<TriangleMesh>(), s.B, 1000, 10), Error);
  EXPECT_THROW(MakeFcl(s.A, s.B, -1, 10), Error);
}

}  // namespace
}  // namespace contactlab
