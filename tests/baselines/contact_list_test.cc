// The contacts every model lists (ContactModel::KeepContacts / LatestContacts), checked against
// the geometry of a ball pressed into a plate, not against the models' own code: a point in
// contact lies in both bodies, its depth is its distance below the plate's top face (the
// closed form, within the field's accuracy), and the contacts add up to the model's force
// under the model's own law (the paper's eq. (1) for the pointshell family, FCL's and Bullet's
// penalty contacts, the pressure integral for pressure-field).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <string>

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

constexpr double kR = 0.02;       // the ball's radius (testing::BallOnPlate), metres
constexpr double kDepth = 0.002;  // how deep the ball is pressed into the plate, metres
constexpr double kRes = 24;       // field cells along each body's box (BallOnPlate default)

// The ball (pointshell role, A) kDepth into the plate (field role, B), whose top face is z = 0.
struct Pressed {
  testing::TempDir cache;
  Scene scene;
  std::unique_ptr<SceneAssets> assets;
  Eigen::Vector3d centre{0, 0, kR - kDepth};  // the ball's centre, world

  Pressed() {
    RegisterContactModels();
    testing::BallOnPlate b;
    b.ball_z = kR - kDepth;
    b.points = 2048;
    b.levels = 3;
    scene = ParseScene(ConfigNode::LoadString(b.Yaml(), "contact_list_test"));
    assets = std::make_unique<SceneAssets>(scene, testing::Assets(cache));
  }
  ContactQuery Query() const {
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    q.node_budget = 0;
    return q;
  }
};

Pressed& Scene0() {
  static Pressed p;
  return p;
}

// Evaluates NAME at the pressed poses with its contacts kept. HAS: whether it lists any.
struct Listed {
  ContactResult r;
  ContactList contacts;
  bool has = false;
};
Listed Evaluate(const std::string& name) {
  Pressed& s = Scene0();
  auto model = MakeSceneContactModel(name, s.scene, *s.assets);
  Listed out;
  out.has = model->KeepContacts(1 << 16);
  out.r = model->Evaluate(s.Query());
  model->LatestContacts(&out.contacts);
  return out;
}

// The contacts' sum of k depth normal (force) and its moment about B's origin.
Wrench PenaltySum(const ContactList& c, double k, const Eigen::Vector3d& o_B) {
  Wrench w;
  for (int i = 0; i < c.size(); ++i) {
    const Eigen::Vector3d f = k * c.depths[std::size_t(i)] * c.normals[std::size_t(i)];
    w.force += f;
    w.torque += (c.points[std::size_t(i)] - o_B).cross(f);
  }
  return w;
}

void ExpectWellFormed(const std::string& name, const ContactList& c) {
  ASSERT_EQ(c.normals.size(), c.points.size()) << name;
  ASSERT_EQ(c.depths.size(), c.points.size()) << name;
  EXPECT_EQ(c.not_kept, 0) << name;
  for (int i = 0; i < c.size(); ++i) {
    EXPECT_TRUE(c.points[std::size_t(i)].allFinite()) << name << " contact " << i;
    EXPECT_NEAR(c.normals[std::size_t(i)].norm(), 1.0, 1e-6) << name << " contact " << i;
    EXPECT_GE(c.depths[std::size_t(i)], 0.0) << name << " contact " << i;
  }
}

// The paper's model and its variants: one contact per point in contact, on the ball's
// pointshell and in the plate, at its closed-form depth below the plate, pushing the plate
// along the ball's outward radius (the force is along each point's normal, eq. (1), and the
// ball's normals are radial, not the plate's), and k_C depth normal summed over them is the
// model's wrench.
TEST(ContactList, PointshellContactsArePointsInContactAtTheirDepthBelowThePlate) {
  Pressed& s = Scene0();
  const double h_B = s.assets->B.field()->spacing();
  // Pointshell points sit on an offset surface half a cell of A's field outside A's mesh.
  const double shell_radius = kR + s.assets->A.field()->spacing();
  for (const std::string name : {"pointshell", "pointshell-linear", "vps", "vps-repulsion"}) {
    const Listed l = Evaluate(name);
    ASSERT_TRUE(l.has) << name;
    ExpectWellFormed(name, l.contacts);
    const ContactList& c = l.contacts;
    EXPECT_EQ(c.size(), l.r.stats.points_in_contact) << name;
    EXPECT_GT(c.size(), 10) << name;
    double worst_depth = 0, worst_angle = 0;
    for (int i = 0; i < c.size(); ++i) {
      const Eigen::Vector3d& p = c.points[std::size_t(i)];
      const Eigen::Vector3d& n = c.normals[std::size_t(i)];
      EXPECT_LE((p - s.centre).norm(), shell_radius) << name << " point " << i << " off the ball's pointshell";
      EXPECT_LE(p.z(), 0.25 * h_B) << name << " point " << i << " above the plate";
      worst_depth = std::max(worst_depth, std::abs(c.depths[std::size_t(i)] - (-p.z())));
      worst_angle = std::max(worst_angle, std::acos(std::min(1.0, n.dot((p - s.centre).normalized()))));
      EXPECT_LT(n.z(), 0) << name << " contact " << i << " does not push the plate down";
    }
    std::printf("%s: %d contacts, worst depth error %.3g m (h_B %.3g m), worst normal angle %.3g rad\n",
                name.c_str(), c.size(), worst_depth, h_B, worst_angle);
    // Pointshell points lie on the ball within a fraction of a cell; the field (linear across
    // the plate's top) gives their depth within rounding, VPS's layered voxmap to a voxel's
    // share of error.
    EXPECT_LT(worst_depth, 0.1 * h_B) << name;
    EXPECT_LT(worst_angle, 0.1) << name;
    const double k = s.scene.model.penalty.k_C * l.r.stats.stiffness_scale;
    const Wrench sum = PenaltySum(c, k, s.scene.field_body.pose.translation);
    EXPECT_LT((sum.force - l.r.on_B.force).norm(), 1e-5 * l.r.on_B.force.norm()) << name;
    EXPECT_LT((sum.torque - l.r.on_B.torque).norm(), 1e-5 * l.r.on_B.force.norm() * kR + 1e-12) << name;
  }
}

// FCL's triangle-pair contacts and Bullet's manifold points: near both surfaces (the meshes
// are a subdivided sphere and a box; Bullet's points are midpoints of points on the two
// meshes thickened by their 0.5 mm margins), along the plate's normal or the ball's facet
// normals, and k_C depth normal summed is the wrench.
TEST(ContactList, MeshContactsLieOnBothSurfaces) {
  Pressed& s = Scene0();
  for (const std::string name : {"fcl", "bullet"}) {
    // Metres off the plate's top and off the ball: Bullet's midpoints lie within the two
    // margins of the plate, and of the ball where the point on the plate is beside it.
    const double tolerance_z = name == "bullet" ? 2 * 0.0005 + 1e-4 : 1e-4;
    const double tolerance_r = name == "bullet" ? 4 * 0.0005 : 1e-4;
    const Listed l = Evaluate(name);
    ASSERT_TRUE(l.has) << name;
    ExpectWellFormed(name, l.contacts);
    const ContactList& c = l.contacts;
    EXPECT_EQ(c.size(), l.r.stats.points_in_contact) << name;
    EXPECT_GT(c.size(), 0) << name;
    for (int i = 0; i < c.size(); ++i) {
      const Eigen::Vector3d& p = c.points[std::size_t(i)];
      // Within the overlap's depth of the plate's top and of the ball's sphere.
      EXPECT_LE(std::abs(p.z()), kDepth + tolerance_z) << name << " contact " << i;
      EXPECT_LE((p - s.centre).norm(), kR + tolerance_r) << name << " contact " << i;
      EXPECT_LE(c.depths[std::size_t(i)], 2 * kDepth) << name << " contact " << i;
      EXPECT_LT(c.normals[std::size_t(i)].z(), -0.7) << name << " contact " << i << " far from the plate's normal";
    }
    const double k = s.scene.model.penalty.k_C * l.r.stats.stiffness_scale;
    const Wrench sum = PenaltySum(c, k, s.scene.field_body.pose.translation);
    EXPECT_LT((sum.force - l.r.on_B.force).norm(), 1e-9 * (1 + l.r.on_B.force.norm())) << name;
  }
}

// Pressure-field: the surface's polygons, inside both bodies, each area times mean pressure
// along its normal, summing to the force (the integral the model takes) and to the contact area.
TEST(ContactList, PressureFieldPolygonsSumToTheForceAndArea) {
  Pressed& s = Scene0();
  const Listed l = Evaluate("pressure-field");
  ASSERT_TRUE(l.has);
  ExpectWellFormed("pressure-field", l.contacts);
  const ContactList& c = l.contacts;
  ASSERT_GT(c.size(), 0);
  ASSERT_EQ(c.areas.size(), c.points.size());
  ASSERT_EQ(c.pressures.size(), c.points.size());
  const double h = s.assets->B.field()->spacing();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double area = 0;
  for (int i = 0; i < c.size(); ++i) {
    const std::size_t k = std::size_t(i);
    EXPECT_GT(c.areas[k], 0);
    EXPECT_GT(c.pressures[k], 0);
    EXPECT_LE(c.points[k].z(), h) << "polygon " << i << " above the plate";
    EXPECT_LE((c.points[k] - s.centre).norm(), kR + h) << "polygon " << i << " outside the ball";
    EXPECT_LE(c.depths[k], l.r.stats.max_penetration + 1e-12);
    EXPECT_LT(c.normals[k].z(), 0) << "polygon " << i << " does not push the plate down";
    force += c.areas[k] * c.pressures[k] * c.normals[k];
    area += c.areas[k];
  }
  EXPECT_LT((force - l.r.on_B.force).norm(), 1e-9 * l.r.on_B.force.norm());
  EXPECT_NEAR(area, l.r.stats.contact_area, 1e-9 * area);
}

// Inner spheres: each overlapping pair's overlap centre lies in both bodies, at its depth.
TEST(ContactList, InnerSpherePairsOverlapInsideBothBodies) {
  Pressed& s = Scene0();
  const Listed l = Evaluate("inner-spheres");
  ASSERT_TRUE(l.has);
  ExpectWellFormed("inner-spheres", l.contacts);
  const ContactList& c = l.contacts;
  EXPECT_EQ(c.size(), l.r.stats.points_in_contact);
  ASSERT_GT(c.size(), 0);
  double deepest = 0;
  for (int i = 0; i < c.size(); ++i) {
    const Eigen::Vector3d& p = c.points[std::size_t(i)];
    EXPECT_LE(p.z(), 1e-9) << "pair " << i << " above the plate";
    EXPECT_LE((p - s.centre).norm(), kR + 1e-9) << "pair " << i << " outside the ball";
    EXPECT_GT(c.depths[std::size_t(i)], 0);
    deepest = std::max(deepest, c.depths[std::size_t(i)]);
  }
  EXPECT_DOUBLE_EQ(deepest, l.r.stats.max_penetration);
}

// Every registered model either lists well-formed contacts or says it has none; the references
// (a volume integral or quadrature, no discrete contacts) say so, as does a model that never
// asked KeepContacts (an empty list).
TEST(ContactList, EveryModelListsWellFormedContactsOrNone) {
  Pressed& s = Scene0();
  const std::set<std::string> without = {"reference", "volume", "eq2-halfspace"};
  std::vector<std::string> names = ContactModelNames();
  for (const std::string& n : ReferenceModelNames()) names.push_back(n);
  for (const std::string& name : names) {
    std::unique_ptr<ContactModel> model;
    try {
      model = MakeSceneContactModel(name, s.scene, *s.assets);
    } catch (const Error& e) {
      std::printf("%s: not made on this scene (%s)\n", name.c_str(), e.what());
      continue;
    }
    ContactList c;
    c.depths.push_back(1);  // replaced
    model->Evaluate(s.Query());
    model->LatestContacts(&c);
    EXPECT_EQ(c.size(), 0) << name << " listed contacts it was not asked to keep";
    EXPECT_TRUE(c.depths.empty()) << name;
    const bool has = model->KeepContacts(1 << 16);
    EXPECT_EQ(has, !without.count(name)) << name;
    const ContactResult r = model->Evaluate(s.Query());
    model->LatestContacts(&c);
    ExpectWellFormed(name, c);
    if (!has) {
      EXPECT_EQ(c.size(), 0) << name;
    }
    if (name.starts_with("pointshell") || name.starts_with("vps")) {
      EXPECT_EQ(c.size(), r.stats.points_in_contact) << name;
    }
  }
}

// The room kept is a cap: contacts past it are counted, not listed, and the wrench is the same.
TEST(ContactList, ContactsPastTheRoomKeptAreCountedNotListed) {
  Pressed& s = Scene0();
  auto model = MakeSceneContactModel("pointshell", s.scene, *s.assets);
  const ContactResult all = model->Evaluate(s.Query());
  ASSERT_GT(all.stats.points_in_contact, 5);
  ASSERT_TRUE(model->KeepContacts(5));
  const ContactResult r = model->Evaluate(s.Query());
  ContactList c;
  model->LatestContacts(&c);
  EXPECT_EQ(c.size(), 5);
  EXPECT_EQ(c.size() + c.not_kept, r.stats.points_in_contact);
  EXPECT_EQ(r.on_B.force, all.on_B.force);
}

}  // namespace
}  // namespace contactlab
