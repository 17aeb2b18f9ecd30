// The one penalty-parameter type: the L / l rule of the paper (sec. 2.1) and its checks.
#include "contact/penalty_params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "pointshell_contact/pointshell_contact_params.h"
#include "util/config_node.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::ErrorOf;

TEST(PenaltyParams, StiffnessIsKcUntilLPointsTouchThenScaledByLOverL) {
  const PenaltyParams p{.k_C = 600, .L = 10};
  double scale = 0;
  EXPECT_DOUBLE_EQ(p.StiffnessFor(0, &scale), 600);
  EXPECT_DOUBLE_EQ(scale, 1);
  EXPECT_DOUBLE_EQ(p.StiffnessFor(9), 600);
  EXPECT_DOUBLE_EQ(p.StiffnessFor(10), 600);
  // The total stiffness of l >= L points stays that of L points: l * k = L * k_C.
  for (int l : {10, 11, 40, 1000}) EXPECT_NEAR(l * p.StiffnessFor(l, &scale), 10 * 600.0, 1e-9) << l;
  EXPECT_DOUBLE_EQ(scale, 10.0 / 1000);
  const PenaltyParams off{.k_C = 600, .L = 0};
  EXPECT_DOUBLE_EQ(off.StiffnessFor(5000), 600);
}

TEST(PenaltyParams, DefaultsAreThePapersAndEveryModelParamsStartsFromThem) {
  const PenaltyParams p;
  EXPECT_EQ(p.k_C, PenaltyParams::kDefaultStiffness);
  EXPECT_EQ(p.L, PenaltyParams::kDefaultManyPointThreshold);
  EXPECT_EQ(p.L, 10);  // the paper's L (sec. 2.1)
  const PointshellContactParams m;
  EXPECT_EQ(m.penalty.k_C, p.k_C);
  EXPECT_EQ(m.penalty.L, p.L);
}

TEST(PenaltyParams, CheckRejectsZeroNegativeOrNonFiniteStiffnessAndNegativeL) {
  EXPECT_NO_THROW(CheckPenaltyParams({.k_C = 1e-3, .L = 0}, "here"));
  EXPECT_NE(ErrorOf([] { CheckPenaltyParams({.k_C = 0, .L = 10}, "contact model x"); }).find("contact model x: k_C"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { CheckPenaltyParams({.k_C = -1, .L = 10}, "contact model x"); }).find("contact model x: k_C"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { CheckPenaltyParams({.k_C = std::nan(""), .L = 10}, "m"); }).find("k_C"), std::string::npos);
  EXPECT_NE(ErrorOf([] { CheckPenaltyParams({.k_C = 1, .L = -2}, "m"); }).find("m: L"), std::string::npos);
}

// The model section as the paper's model reads it: the shared keys' table
// (contact/contact_params.h) and the paper's own (pointshell_contact/pointshell_contact_params.h),
// reading TEXT as FILE with "other" left to the caller.
PointshellContactParams ParseModel(const std::string& text, const std::string& file,
                                   PointshellContactParams base = {}) {
  const ConfigNode node = ConfigNode::LoadString(text, file);
  std::vector<std::string> own_keys = PointshellOwnParamTable().Keys();
  std::vector<std::string> shared_keys = ContactParamTable().Keys();
  own_keys.push_back("other");
  shared_keys.push_back("other");
  const ContactParams shared{base.penalty, base.coherence, base.max_point_speed, base.cycle_seconds, base.lipschitz};
  const PointshellOwnParams own{base.level, base.cold_fraction, base.gradient};
  return PointshellParamsOf(ContactParamTable().Parse(node, shared, own_keys),
                            PointshellOwnParamTable().Parse(node, own, shared_keys));
}

TEST(PenaltyParams, ParseNamesTheFileLineAndKey) {
  const PenaltyParams p = ParseModel("k_C: 1500\nL: 0\nother: 1\n", "model.yaml").penalty;
  EXPECT_EQ(p.k_C, 1500);
  EXPECT_EQ(p.L, 0);
  // Absent keys keep the base.
  PointshellContactParams base;
  base.penalty = {.k_C = 7, .L = 3};
  const PenaltyParams kept = ParseModel("other: 1\n", "m.yaml", base).penalty;
  EXPECT_EQ(kept.k_C, 7);
  EXPECT_EQ(kept.L, 3);
  std::string e = ErrorOf([] { ParseModel("L: 4\nk_C: -3\n", "model.yaml"); });
  EXPECT_NE(e.find("model.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("k_C"), std::string::npos) << e;
  e = ErrorOf([] { ParseModel("L: -1\n", "model.yaml"); });
  EXPECT_NE(e.find("model.yaml:1"), std::string::npos) << e;
  EXPECT_NE(e.find(": L:"), std::string::npos) << e;
  e = ErrorOf([] { ParseModel("L: 4\nk_C: 0\n", "model.yaml"); });
  EXPECT_NE(e.find("model.yaml:2: k_C: must be in (0, 1e+09], got 0"), std::string::npos) << e;
  e = ErrorOf([] { ParseModel("k_C: stiff\n", "model.yaml"); });
  EXPECT_NE(e.find("'stiff'"), std::string::npos) << e;
  e = ErrorOf([] { ParseModel("k_c: 3\n", "model.yaml"); });
  EXPECT_NE(e.find("model.yaml:1: k_c: unknown key"), std::string::npos) << e;
}

TEST(PointshellContactParams, ParseChecksEveryValueWhereItIsDefined) {
  const PointshellContactParams p = ParseModel(
      "k_C: 800\nL: 5\nlevel: 2\ncoherence: true\nmax_point_speed: 0.5\ncycle_seconds: 0.002\nlipschitz: 1.5\n"
      "cold_fraction: 0.5\ngradient: field\n",
      "m.yaml");
  EXPECT_EQ(p.penalty.k_C, 800);
  EXPECT_EQ(p.penalty.L, 5);
  EXPECT_EQ(p.level, 2);
  EXPECT_TRUE(p.coherence);
  EXPECT_EQ(p.max_point_speed, 0.5);
  EXPECT_EQ(p.cycle_seconds, 0.002);
  EXPECT_EQ(p.lipschitz, 1.5);
  EXPECT_EQ(p.cold_fraction, 0.5);
  EXPECT_EQ(p.gradient, ContactGradient::kField);
  for (const char* bad : {"lipschitz: 0.5", "cold_fraction: 1.5", "level: -2", "max_point_speed: 0", "gradient: up"}) {
    const std::string e = ErrorOf([&] { ParseModel(bad, "m.yaml"); });
    const std::string key = std::string(bad).substr(0, std::string(bad).find(':'));
    EXPECT_NE(e.find("m.yaml:1: " + key), std::string::npos) << bad << " -> " << e;
  }
}

// k_V = k_C L / sqrt(area of A): a face of area A_c pressed into a halfspace by any depth d has
// V = A_c d, so it feels k_V A_c; a cube of side a (area 6a²) pressed flat feels k_C L a² /
// (sqrt(6) a), linear in a as a penalty force is when the scene scales.
TEST(PenaltyParams, VolumeStiffnessGivesAFaceTheForceOfLPointsAndScalesWithTheScene) {
  PenaltyParams p;
  p.k_C = 2000;
  p.L = 10;
  const double a = 0.1, face = a * a, area = 6 * a * a;
  const double force = p.VolumeStiffness(area) * face;  // |grad V| = A_c for a flat face
  EXPECT_NEAR(force, 2000 * 10 * a / std::sqrt(6.0), 1e-9 * force);
  const double scaled = p.VolumeStiffness(area * 9) * face * 9;  // the scene three times larger
  EXPECT_NEAR(scaled, 3 * force, 1e-9 * force);
  p.L = 0;  // the default L
  EXPECT_EQ(p.VolumeStiffness(area), 2000 * PenaltyParams::kDefaultManyPointThreshold / std::sqrt(area));
}

}  // namespace
}  // namespace contactlab
