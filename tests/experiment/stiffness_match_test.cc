// model.stiffness: matched (scene/stiffness_match.h), checked against what it claims, not
// against its own arithmetic: a scaled wrench is the model at scaled stiffness (the paper's
// model at twice k_C, the pressure field at twice its moduli), the matched factor of a model
// that does not read k_C follows the paper's model's k_C exactly, and on the reference press,
// found here from the meshes' geometry alone, every matched model pushes back as hard as the
// paper's model and in its direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "contact/register_contact_models.h"
#include "contact/scaled_contact_model.h"
#include "experiment/deformable_fixture.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene/stiffness_match.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {
namespace {

// The ball (A) 1.5 mm into the plate (B, top face z = 0), with MODEL_KEYS in the model block
// and, when MODULUS > 0, that modulus on both bodies' pressure fields.
std::string BallYaml(double k_C, const std::string& model_keys, double modulus = 0, double ball_z = 0.0185) {
  testing::BallOnPlate b;
  b.ball_z = ball_z;
  b.points = 1024;
  b.levels = 3;
  b.k_C = 0;
  std::string yaml = b.Yaml();
  if (modulus > 0) {
    const std::string block = "    pressure_field: {modulus: " + std::to_string(modulus) + "}\n";
    for (const std::string role : {"    role: pointshell\n", "    role: field\n"}) {
      yaml.insert(yaml.find(role) + role.size(), block);
    }
  }
  return yaml + "model: {k_C: " + std::to_string(k_C) + (model_keys.empty() ? "" : ", " + model_keys) + "}\n";
}

struct Loaded {
  Scene scene;
  std::unique_ptr<SceneAssets> assets;
  Loaded(const std::string& yaml, const testing::TempDir& cache) {
    RegisterContactModels();
    scene = ParseScene(ConfigNode::LoadString(yaml, "ball-plate.yaml"));
    scene.file = "ball-plate.yaml";
    assets = std::make_unique<SceneAssets>(scene, testing::Assets(cache));
  }
  ContactResult At(const std::string& model) {
    auto m = MakeSceneContactModel(model, scene, *assets);
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    return m->Evaluate(q);
  }
};

void ExpectScaled(const ContactResult& twice, const ContactResult& once, double s) {
  ASSERT_GT(once.on_B.force.norm(), 0);
  EXPECT_LT((twice.on_B.force - s * once.on_B.force).norm(), 1e-9 * twice.on_B.force.norm());
  EXPECT_LT((twice.on_B.torque - s * once.on_B.torque).norm(), 1e-9 * twice.on_B.torque.norm() + 1e-15);
  EXPECT_LT((twice.K_B - s * once.K_B).norm(), 1e-9 * twice.K_B.norm());
}

TEST(StiffnessMatch, AScaledWrenchIsTheModelAtThatStiffness) {
  testing::TempDir cache;
  // The paper's model: k_C = 2000 against k_C = 1000 scaled by 2.
  Loaded soft(BallYaml(1000, ""), cache), stiff(BallYaml(2000, ""), cache);
  ContactQuery q;
  q.X_WA = soft.scene.pointshell_body.pose;
  q.X_WB = soft.scene.field_body.pose;
  ScaledContactModel scaled(MakeSceneContactModel("pointshell", soft.scene, *soft.assets), 2.0);
  ExpectScaled(stiff.At("pointshell"), scaled.Evaluate(q), 1.0);
  // The pressure field: both moduli doubled against the wrench scaled by 2; its contact list's
  // pressures double, its areas and depths stay.
  Loaded pf1(BallYaml(1000, "", 1e5), cache), pf2(BallYaml(1000, "", 2e5), cache);
  ScaledContactModel scaled_pf(MakeSceneContactModel("pressure-field", pf1.scene, *pf1.assets), 2.0);
  ASSERT_TRUE(scaled_pf.KeepContacts(1 << 14));
  auto plain_pf = MakeSceneContactModel("pressure-field", pf2.scene, *pf2.assets);
  ASSERT_TRUE(plain_pf->KeepContacts(1 << 14));
  ExpectScaled(plain_pf->Evaluate(q), scaled_pf.Evaluate(q), 1.0);
  ContactList a, b;
  scaled_pf.LatestContacts(&a);
  plain_pf->LatestContacts(&b);
  ASSERT_GT(a.size(), 0);
  ASSERT_EQ(a.size(), b.size());
  for (int i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a.pressures[i], b.pressures[i], 1e-9 * b.pressures[i]);
    EXPECT_DOUBLE_EQ(a.areas[i], b.areas[i]);
  }
  EXPECT_EQ(WrenchScaleOf(scaled_pf), 2.0);
  EXPECT_EQ(WrenchScaleOf(*plain_pf), 1.0);
}

TEST(StiffnessMatch, TheMatchedFactorFollowsThePaperModelsStiffness) {
  testing::TempDir cache;
  // The pressure field reads no k_C, the paper's model's force is linear in it: doubling k_C
  // doubles the factor.
  Loaded k1(BallYaml(1000, "stiffness: matched"), cache), k2(BallYaml(2000, "stiffness: matched"), cache);
  const auto m1 = MakeSceneContactModel("pressure-field", k1.scene, *k1.assets);
  const auto m2 = MakeSceneContactModel("pressure-field", k2.scene, *k2.assets);
  const double s1 = WrenchScaleOf(*m1), s2 = WrenchScaleOf(*m2);
  EXPECT_GT(s1, 10.0);  // its own 1e5 Pa pushes back far more softly than 1000 N/m a point
  EXPECT_NEAR(s2 / s1, 2.0, 1e-9);
  // The paper's model is never scaled, nor is anything under own.
  EXPECT_EQ(WrenchScaleOf(*MakeSceneContactModel("pointshell", k1.scene, *k1.assets)), 1.0);
  Loaded own(BallYaml(1000, ""), cache);
  EXPECT_EQ(WrenchScaleOf(*MakeSceneContactModel("pressure-field", own.scene, *own.assets)), 1.0);
}

TEST(StiffnessMatch, OnTheReferencePressEveryModelPushesBackLikeThePapers) {
  testing::TempDir cache;
  // The reference press from the geometry alone: the ball's lowest mesh vertex on the plate's
  // top face (z = 0), then match_depth (1 mm) lower.
  Loaded probe(BallYaml(1000, ""), cache);
  double lowest = 0;
  for (const Eigen::Vector3d& v : probe.assets->A.mesh()->vertices) lowest = std::min(lowest, v.z());
  const double pressed_z = -lowest - 1e-3;
  Loaded at(BallYaml(1000, "stiffness: matched", 0, pressed_z), cache);
  const Eigen::Vector3d paper = at.At("pointshell").on_B.force;
  ASSERT_GT(paper.norm(), 1.0);
  for (const std::string model : {"pressure-field", "pointshell-linear", "fcl", "vps"}) {
    const Eigen::Vector3d f = at.At(model).on_B.force;
    EXPECT_NEAR(f.norm() / paper.norm(), 1.0, 0.01) << model << ": " << f.transpose() << " against " << paper.transpose();
    EXPECT_GT(f.normalized().dot(paper.normalized()), 0.99) << model;
  }
}

TEST(StiffnessMatch, APressWithNoDirectionIsRefusedNamingTheScene) {
  testing::TempDir cache;
  // The ball's origin on the plate's: no direction to press along.
  Loaded same(BallYaml(1000, "stiffness: matched", 0, -0.01), cache);
  try {
    MakeSceneContactModel("pressure-field", same.scene, *same.assets);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ball-plate.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("stiffness: matched"), std::string::npos) << what;
    EXPECT_NE(what.find("same point"), std::string::npos) << what;
  }
  // A value that is neither own nor matched is refused by the scene's table.
  EXPECT_THROW(ParseScene(ConfigNode::LoadString(BallYaml(1000, "stiffness: soft"), "x.yaml")), Error);
}

}  // namespace
}  // namespace contactlab
