// Tests of the Bullet baseline (baselines/bullet): wrench sign (Bullet's m_normalWorldOnB points from B to A),
// torque about B's origin, zero wrench when apart, K_B against finite differences.
#include "baselines/bullet/bullet_contact_model.h"

#include <gtest/gtest.h>

#include "penalty_model_checks.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::unique_ptr<ContactModel> MakeBullet(std::shared_ptr<const TriangleMesh> A, std::shared_ptr<const TriangleMesh> B,
                                      double k_C, int L) {
  BulletContactParams p;
  p.penalty.k_C = k_C;
  p.penalty.L = L;
  return std::make_unique<BulletContactModel>(std::move(A), std::move(B), p);
}

TEST(BulletContactModel, ForceOnBPointsAwayFromA) { testing::ExpectForceOnBPointsAwayFromA(MakeBullet); }
TEST(BulletContactModel, TorqueIsAboutBsOrigin) { testing::ExpectTorqueAboutBsOrigin(MakeBullet); }
TEST(BulletContactModel, ZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeBullet); }
TEST(BulletContactModel, TranslationGradientMatchesFiniteDifferences) {
  testing::ExpectTranslationGradientMatchesFiniteDifferences(MakeBullet);
}

TEST(BulletContactModel, RejectsEmptyMeshAndNegativeStiffness) {
  testing::BoxOnBox s;
  EXPECT_THROW(MakeBullet(std::make_shared<TriangleMesh>(), s.B, 1000, 10), Error);
  EXPECT_THROW(MakeBullet(s.A, s.B, -1, 10), Error);
}

}  // namespace
}  // namespace contactlab
