// Friction as scenes ask for it (contact/friction.h): the `friction:` block of the model section,
// its checks, and which registered models carry it. A model that carries none must refuse a
// scene asking for friction, naming itself and the models that do; one that carries it between
// rigid bodies must refuse a deformable body.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "allocation_counter.h"
#include "contact/model_registry.h"
#include "contact/register_contact_models.h"
#include "experiment/deformable_fixture.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {
namespace {

Scene BallOnPlateWith(const std::string& model) {
  testing::BallOnPlate b;
  b.k_C = 0;  // the model block below instead
  return ParseScene(ConfigNode::LoadString(b.Yaml() + "model: " + model + "\n", "friction.yaml"));
}

TEST(FrictionScenes, TheBlockReadsItsCoefficientsAndTheDynamicOneDefaultsToTheStatic) {
  const Scene off = BallOnPlateWith("{k_C: 1000}");
  EXPECT_FALSE(off.model.friction.on()) << "friction is off by default";
  const Scene on = BallOnPlateWith("{k_C: 1000, friction: {static: 0.6, stiffness: 500}}");
  EXPECT_TRUE(on.model.friction.on());
  EXPECT_DOUBLE_EQ(on.model.friction.mu_static, 0.6);
  EXPECT_DOUBLE_EQ(on.model.friction.mu_dynamic, 0.6);
  EXPECT_DOUBLE_EQ(on.model.friction.tangential_stiffness, 500);
  const Scene both = BallOnPlateWith("{friction: {static: 0.6, dynamic: 0.2}}");
  EXPECT_DOUBLE_EQ(both.model.friction.mu_dynamic, 0.2);
}

TEST(FrictionScenes, APairTakesItsOwnFriction) {
  // A tool among three bodies: friction on against the floor only, from the pair's own section.
  const Scene scene = ParseScene(ConfigNode::LoadString(
      "name: pairs\n"
      "tool: ball\n"
      "bodies:\n"
      "  - {name: ball, mesh: \"sphere:0.02,2\", role: pointshell}\n"
      "  - {name: floor, mesh: \"box:0.1,0.1,0.01\", pose: [0, 0, -0.01, 1, 0, 0, 0], role: field}\n"
      "  - {name: wall, mesh: \"box:0.01,0.1,0.04\", pose: [0.03, 0, 0.04, 1, 0, 0, 0], role: field}\n"
      "pairs:\n"
      "  - {bodies: [ball, floor], params: {k_C: 1000, friction: {static: 0.5, dynamic: 0.4}}}\n"
      "model: {k_C: 1000}\n",
      "pairs.yaml"));
  int with_friction = 0;
  for (const PairSpec& pair : scene.pairs) {
    const ContactParams& p = pair.has_params ? pair.params : scene.model;
    const bool floor = scene.bodies[std::size_t(pair.bodies[1])].name == "floor" ||
                       scene.bodies[std::size_t(pair.bodies[0])].name == "floor";
    EXPECT_EQ(p.friction.on(), floor) << pair.where;
    if (p.friction.on()) {
      EXPECT_DOUBLE_EQ(p.friction.mu_dynamic, 0.4);
      ++with_friction;
    }
  }
  EXPECT_EQ(with_friction, 1);
}

TEST(FrictionScenes, BadCoefficientsAreRefusedNamingTheFileAndTheKey) {
  const struct {
    const char* model;
    const char* says;
  } cases[] = {
      {"{friction: {static: 0.3, dynamic: 0.5}}", "must not exceed static"},
      {"{friction: {static: -0.1}}", "static"},
      {"{friction: {static: 0.5, stiffness: 0}}", "stiffness"},
      {"{friction: {static: 0.5, mu: 0.2}}", "mu"},
      {"{friction: 0.5}", "friction"},
  };
  for (const auto& c : cases) {
    try {
      BallOnPlateWith(c.model);
      ADD_FAILURE() << c.model << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("friction.yaml"), std::string::npos) << what;
      EXPECT_NE(what.find(c.says), std::string::npos) << what;
    }
  }
}

TEST(FrictionScenes, AModelWithoutFrictionRefusesASceneThatAsksForIt) {
  RegisterContactModels();
  const Scene scene = BallOnPlateWith("{k_C: 1000, friction: {static: 0.5}}");
  int carrying = 0;
  for (const std::string& name : ContactModelNames()) {
    const ContactModelEntry& e = *FindContactModel(name);
    auto check = [&] {
      CheckContactModel(name, scene.model, scene.model_params, "ball", false, "plate", false, "friction.yaml");
    };
    if (e.friction == FrictionSupport::kNone) {
      try {
        check();
        ADD_FAILURE() << name << " accepted friction it does not carry";
      } catch (const Error& err) {
        const std::string what = err.what();
        EXPECT_NE(what.find("'" + name + "' carries no friction"), std::string::npos) << what;
        EXPECT_NE(what.find("pointshell"), std::string::npos) << "names the models that carry it: " << what;
      }
    } else {
      EXPECT_NO_THROW(check()) << name;
      ++carrying;
    }
  }
  EXPECT_GE(carrying, 2) << "the paper's two variants carry friction";
  // Off, every model takes the scene.
  const Scene off = BallOnPlateWith("{k_C: 1000}");
  for (const std::string& name : ContactModelNames()) {
    EXPECT_NO_THROW(CheckContactModel(name, off.model, off.model_params, "ball", false, "plate", false, "f.yaml"))
        << name;
  }
}

TEST(FrictionScenes, FrictionWithADeformableBodyIsRefused) {
  RegisterContactModels();
  testing::BeamUnderProbe beam;
  beam.model = "{k_C: 1000, L: 10, friction: {static: 0.5}}";
  const Scene scene = ParseScene(ConfigNode::LoadString(beam.Yaml(), "beam.yaml"));
  try {
    CheckContactModel("pointshell", scene.model, scene.model_params, "beam", true, "probe", false, "beam.yaml");
    ADD_FAILURE() << "friction on a deformable pointshell was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rigid bodies only"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'beam' is deformable"), std::string::npos) << e.what();
  }
}

// A scene-built model dragged: A at its scene pose, moved along x by each offset in turn, one
// query each; at each, the friction on B along x (the force less that of the same model without
// friction at the same pose: a lateral part of the normal forces, as where a patch's edge points
// tilt unevenly, is no friction) and the normal force (-z, the plate's normal).
// Also counts the heap allocations of MODEL's queries after the first.
struct Drag {
  std::vector<double> along, normal;
  long allocations = 0;
};
Drag DragAlong(ContactModel& model, ContactModel& frictionless, const Scene& scene, const std::vector<double>& offsets) {
  Drag d;
  d.along.reserve(offsets.size()), d.normal.reserve(offsets.size());
  std::int64_t cycle = 0;
  for (double x : offsets) {
    ContactQuery q;
    q.cycle = cycle++;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WA.translation.x() += x;
    q.X_WB = scene.field_body.pose;
    const long before = testing::AllocationCount();
    const ContactResult r = model.Evaluate(q);
    if (cycle > 1) d.allocations += testing::AllocationCount() - before;
    const ContactResult r0 = frictionless.Evaluate(q);
    d.along.push_back(r.on_B.force.x() - r0.on_B.force.x());
    d.normal.push_back(-r0.on_B.force.z());
  }
  return d;
}

// What a drag 0 -> 0.8 mm -> 0 (1 µm steps) shows against Coulomb's closed form with mu_s 0.5,
// mu_d 0.3: the relative errors of the peak (against mu_s F_n), of the forward slide, and of the
// slide back (against mu_d F_n, at the same query's F_n).
struct DragErrors {
  double peak, slide, back;
};
DragErrors Errors(const Drag& d) {
  std::size_t peak_at = 0, low_at = 0;
  for (std::size_t k = 0; k < d.along.size(); ++k) {
    if (d.along[k] > d.along[peak_at]) peak_at = k;
    if (d.along[k] < d.along[low_at]) low_at = k;
  }
  const std::size_t turn = 800, last = d.along.size() - 1;
  return {d.along[peak_at] / (0.5 * d.normal[peak_at]) - 1, d.along[turn] / (0.3 * d.normal[turn]) - 1,
          -d.along[last] / (0.3 * d.normal[last]) - 1};
}

std::vector<double> ThereAndBack() {
  std::vector<double> x;
  for (int i = 0; i <= 800; ++i) x.push_back(1e-6 * i);
  for (int i = 799; i >= 0; --i) x.push_back(1e-6 * i);
  return x;
}

// A block of 4 x 4 x 2 cm (the pointshell body) with its mesh 0.5 mm into a plate: a flat contact.
std::string BlockOnPlate() {
  return "name: block-plate\n"
         "bodies:\n"
         "  - {name: block, mesh: \"box:0.02,0.02,0.01,8\", pose: [0, 0, 0.0095, 1, 0, 0, 0], role: pointshell,\n"
         "     pointshell: {points: 4096, levels: 3, seed: 1}, field: {resolution: 48}}\n"
         "  - {name: plate, mesh: \"box:0.1,0.1,0.02\", pose: [0, 0, -0.02, 1, 0, 0, 0], role: field,\n"
         "     field: {resolution: 96}}\n";
}

// Every model that carries friction, on a flat contact (the block) and a curved one (a ball of
// 2 cm radius, its mesh 0.5 mm into the plate): dragged along the surface and back, the friction
// along the motion peaks at mu_s F_n and slides at mu_d F_n each way, within 2 %. Each contact's
// friction lies in the tangent plane of its own normal, so where the normals of a patch fan out
// (the block's edges, the ball) the contacts' loads sum to a little more than the net normal
// force. tests/pointshell_contact/friction_test.cc holds the closed forms on exact geometry.
TEST(FrictionScenes, EveryModelThatCarriesFrictionMeetsCoulombsClosedForm) {
  RegisterContactModels();
  testing::TempDir cache;
  const std::string model = "model: {k_C: 1000, L: 0, friction: {static: 0.5, dynamic: 0.3, stiffness: 2000}}\n";
  testing::BallOnPlate ball;
  ball.k_C = 0;
  ball.ball_z = 0.02 - 0.0005;
  ball.points = 8192;
  ball.levels = 3;
  const Scene flat = ParseScene(ConfigNode::LoadString(BlockOnPlate() + model, "block.yaml"));
  const Scene curved = ParseScene(ConfigNode::LoadString(ball.Yaml() + model, "ball.yaml"));
  SceneAssets flat_assets(flat, testing::Assets(cache)), curved_assets(curved, testing::Assets(cache));
  int models = 0;
  for (const std::string& name : ContactModelNames()) {
    if (FindContactModel(name)->friction == FrictionSupport::kNone) continue;
    ++models;
    for (const bool is_flat : {true, false}) {
      const Scene& scene = is_flat ? flat : curved;
      SceneAssets& assets = is_flat ? flat_assets : curved_assets;
      auto m = MakeSceneContactModel(name, scene, assets);
      Scene without = scene;
      without.model.friction = {};
      auto m0 = MakeSceneContactModel(name, without, assets);
      ASSERT_TRUE(m->KeepContacts(1 << 16));
      const Drag drag = DragAlong(*m, *m0, scene, ThereAndBack());
      ContactList list;
      m->LatestContacts(&list);
      EXPECT_EQ(list.tangential.size(), std::size_t(list.size())) << name;
      ASSERT_GT(drag.normal[0], 0) << name;
      const DragErrors e = Errors(drag);
      std::printf("%-18s %-6s F_n %8.4f N: peak %+.2f %%, slide %+.2f %%, slide back %+.2f %%\n", name.c_str(),
                  is_flat ? "flat" : "curved", drag.normal[0], 100 * e.peak, 100 * e.slide, 100 * e.back);
      if (!FindContactModel(name)->allocates) EXPECT_EQ(drag.allocations, 0) << name << " allocated with friction on";
      const double tol = 0.02;
      EXPECT_LT(std::abs(e.peak), tol) << name << (is_flat ? " flat" : " curved");
      EXPECT_LT(std::abs(e.slide), tol) << name << (is_flat ? " flat" : " curved");
      EXPECT_LT(std::abs(e.back), tol) << name << (is_flat ? " flat" : " curved");
    }
  }
  EXPECT_GE(models, 2);
}

}  // namespace
}  // namespace contactlab
