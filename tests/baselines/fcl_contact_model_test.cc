// Tests of the FCL baseline (baselines/fcl): wrench sign (FCL's normal from object 1 to 2),
// torque about B's origin, zero wrench when apart, K_B against finite differences.
#include "baselines/fcl/fcl_contact_model.h"

#include <gtest/gtest.h>

#include "penalty_model_checks.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::unique_ptr<ContactModel> MakeFcl(std::shared_ptr<const TriangleMesh> A, std::shared_ptr<const TriangleMesh> B,
                                      double k_C, int L) {
  FclContactParams p;
  p.penalty.k_C = k_C;
  p.penalty.L = L;
  return std::make_unique<FclContactModel>(std::move(A), std::move(B), p);
}

TEST(FclContactModel, ForceOnBPointsAwayFromA) { testing::ExpectForceOnBPointsAwayFromA(MakeFcl); }
TEST(FclContactModel, TorqueIsAboutBsOrigin) { testing::ExpectTorqueAboutBsOrigin(MakeFcl); }
TEST(FclContactModel, ZeroWrenchWhenApart) { testing::ExpectZeroWrenchWhenApart(MakeFcl); }
TEST(FclContactModel, TranslationGradientMatchesFiniteDifferences) {
  testing::ExpectTranslationGradientMatchesFiniteDifferences(MakeFcl);
}

TEST(FclContactModel, RejectsEmptyMeshAndNegativeStiffness) {
  testing::BoxOnBox s;
  EXPECT_THROW(MakeFcl(std::make_shared<TriangleMesh>(), s.B, 1000, 10), Error);
  EXPECT_THROW(MakeFcl(s.A, s.B, -1, 10), Error);
}

}  // namespace
}  // namespace contactlab
