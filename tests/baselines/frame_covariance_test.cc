// Frame covariance of every registered contact model (issue 15): turning and moving the whole
// scene — both bodies by one rigid motion G of the world — turns the wrench on B with it:
// F' = R_G F and, about B's moved origin, τ' = R_G τ. Nothing about contact depends on where
// the world's axes are, so a model that breaks this has a preferred direction (an axis-aligned
// step, a world-frame tolerance). Three contacts (ball on a plate, crossed bars, a cube's corner
// into a block), each under three motions, both role orders; the paper's model also with
// deformable bodies at a non-zero q, whose reduced forces (body frame) must not change.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "contact/register_contact_models.h"
#include "contact/model_registry.h"
#include "scene/scene.h"
#include "experiment/deformable_fixture.h"
#include "scene/scene_assets.h"
#include "test_support.h"
#include "util/config_node.h"

namespace contactlab {
namespace {

struct Contact {
  const char* name;
  const char* mesh_A;
  const char* mesh_B;
  Pose X_WA, X_WB;
};

// DEFORMABLE_A / _B: the body carries a small reduced model (linear modal, 4 modes on an
// 8-cell tet mesh, free; as B its deformed field has the default single domain).
std::string SceneText(const Contact& c, bool deformable_A = false, bool deformable_B = false) {
  const std::string deformable = ", deformable: {model: linear, modes: 4, cells: 8}";
  std::string s = std::string("name: covariance\nbodies:\n") +
                  "  - {name: a, mesh: \"" + c.mesh_A + "\", role: pointshell, pointshell: {points: 2048, levels: 3},"
                  " field: {resolution: 48}" + (deformable_A ? deformable : "") + "}\n" +
                  "  - {name: b, mesh: \"" + c.mesh_B + "\", role: field, pointshell: {points: 2048, levels: 3},"
                  " field: {resolution: 48}" + (deformable_B ? deformable : "") + "}\n" +
                  "model: {k_C: 1000, L: 10, coherence: false}\n";
  return s;
}

Pose Turned(const Eigen::Vector3d& w, const Eigen::Vector3d& t) { return {RotationFromVector(w), t}; }

std::vector<Contact> Contacts() {
  const double e = 0.004 * std::sqrt(2.0);
  return {
      {"ball-on-plate", "sphere:0.01,3", "box:0.03,0.03,0.005,3", Turned({0.2, 0.1, -0.3}, {0.001, -0.002, 0.0135}),
       Pose::Identity()},
      {"crossed-bars", "box:0.02,0.004,0.004,3", "box:0.004,0.02,0.004,3",
       Turned({M_PI / 4, 0, 0}, {0.0004, -0.0003, 2 * e - 0.001}), Turned({0, M_PI / 4, 0}, {0, 0, 0})},
      {"corner-into-block", "box:0.01,0.01,0.01,3", "box:0.03,0.03,0.01,3",
       Pose{Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(-1, -1, -1).normalized(), -Eigen::Vector3d::UnitZ()),
            Eigen::Vector3d(0.0002, 0.0001, 0.01 + 0.01 * std::sqrt(3.0) - 0.002)},
       Pose::Identity()},
  };
}

const std::vector<Pose>& Motions() {
  static const std::vector<Pose> motions = {Turned({0, 0, 1.1}, {0.3, -0.2, 0.1}), Turned({0.7, -0.4, 0.9}, {0, 0, 0}),
                                            Turned({-2.0, 0.5, 0.3}, {-1.0, 2.0, 0.5})};
  return motions;
}

TEST(FrameCovariance, EveryModelTurnsItsWrenchWithTheScene) {
  RegisterContactModels();
  testing::TempDir cache;
  const AssetOptions options = testing::Assets(cache);
  const std::vector<Pose>& motions = Motions();
  std::map<std::string, int> touched;  // contacts each model was checked on
  for (const Contact& c : Contacts()) {
    for (int order = 0; order < 2; ++order) {
      const Scene base = ParseScene(ConfigNode::LoadString(SceneText(c), std::string(c.name) + ".yaml"));
      const Scene scene = order == 0 ? base : base.Swapped();
      SceneAssets assets(scene, options);
      const Pose X_WA = order == 0 ? c.X_WA : c.X_WB, X_WB = order == 0 ? c.X_WB : c.X_WA;
      for (const std::string& name : ContactModelNames()) {
        std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, scene, assets);
        ContactQuery q;
        q.X_WA = X_WA;
        q.X_WB = X_WB;
        const ContactResult r = model->Evaluate(q);
        if (r.on_B.force.norm() == 0) {
          // Inner spheres stop short of the bars' edges (1 mm deep): no sphere pair meets there.
          // Every other model and contact must touch, or the check would be empty.
          const bool shallow = name == "inner-spheres" && std::string(c.name) == "crossed-bars";
          if (shallow) {
            std::printf("covariance %s %s %s: no contact (no sphere pair reaches the edges)\n", name.c_str(), c.name,
                        order == 0 ? "AB" : "BA");
            continue;
          }
          FAIL() << name << " " << c.name << " order " << order << ": no contact";
        }
        ++touched[name];
        double worst = 0;
        for (const Pose& G : motions) {
          model->Reset();
          ContactQuery g;
          g.X_WA = G * X_WA;
          g.X_WB = G * X_WB;
          const ContactResult m = model->Evaluate(g);
          const Eigen::Matrix3d R = G.rotation.toRotationMatrix();
          const double scale = r.on_B.force.norm();
          const double torque_scale = std::max(r.on_B.torque.norm(), scale * 0.01);
          worst = std::max({worst, (m.on_B.force - R * r.on_B.force).norm() / scale,
                            (m.on_B.torque - R * r.on_B.torque).norm() / torque_scale});
        }
        std::printf("covariance %s %s %s: largest relative change %.3g\n", name.c_str(), c.name,
                    order == 0 ? "AB" : "BA", worst);
        // Measured: 1e-16 to 1e-12 for every model and contact but one. Bullet's edge-edge
        // contacts between the crossed bars change by 41-43 % when the world's axes turn (the
        // cause inside its GImpact contact generation is not traced): a finding, printed, not
        // failed.
        const bool finding = name == "bullet" && std::string(c.name) == "crossed-bars";
        if (finding) {
          std::printf("FINDING covariance bullet crossed-bars %s: %.3g (edge-edge contacts depend on the world's axes)\n",
                      order == 0 ? "AB" : "BA", worst);
        } else {
          EXPECT_LT(worst, 1e-6) << name << " " << c.name << (order == 0 ? " AB" : " BA");
        }
      }
    }
  }
  for (const std::string& name : ContactModelNames()) EXPECT_GE(touched[name], 4) << name;
}

// The paper's model in its four combinations of (rigid | deformable pointshell) x (grid |
// deformed field), each deformable body at a random non-zero q: q is in body coordinates, so it
// is the same when the scene turns, and so are the reduced contact forces (body frame), while
// the wrench turns with the scene.
TEST(FrameCovariance, DeformableBodiesTurnTheirWrenchAndKeepTheirReducedForces) {
  testing::TempDir cache;
  const AssetOptions options = testing::Assets(cache);
  std::mt19937 rng(3);
  double worst_wrench = 0, worst_reduced = 0;
  for (const Contact& c : Contacts()) {
    for (int order = 0; order < 2; ++order) {
      for (const bool defo_A : {false, true}) {
        for (const bool defo_B : {false, true}) {
          const bool A_is_a = order == 0;
          const Scene base = ParseScene(ConfigNode::LoadString(
              SceneText(c, A_is_a ? defo_A : defo_B, A_is_a ? defo_B : defo_A), std::string(c.name) + ".yaml"));
          const Scene scene = order == 0 ? base : base.Swapped();
          SceneAssets assets(scene, options);
          const Pose X_WA = order == 0 ? c.X_WA : c.X_WB, X_WB = order == 0 ? c.X_WB : c.X_WA;
          // Deformations moving a simulation vertex by up to 0.5 mm: the contacts stay.
          const ReducedState q_A = defo_A ? testing::RandomState(*assets.A.reduced_model(), 5e-4, &rng) : ReducedState();
          const ReducedState q_B = defo_B ? testing::RandomState(*assets.B.reduced_model(), 5e-4, &rng) : ReducedState();
          const std::string what = std::string(c.name) + (order == 0 ? " AB " : " BA ") +
                                   (defo_A ? "deformable A x " : "rigid A x ") + (defo_B ? "deformed B" : "grid B");
          for (const char* name : {"pointshell", "pointshell-linear"}) {
            std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, scene, assets);
            auto evaluate = [&](const Pose& G, ReducedVector* f_A, ReducedVector* f_B) {
              const BodyDeformation d_A{&q_A, f_A}, d_B{&q_B, f_B};
              ContactQuery q;
              q.X_WA = G * X_WA;
              q.X_WB = G * X_WB;
              if (defo_A) q.deformation_A = &d_A;
              if (defo_B) q.deformation_B = &d_B;
              model->Reset();
              return model->Evaluate(q);
            };
            ReducedVector f_A, f_B;
            const ContactResult r = evaluate(Pose::Identity(), &f_A, &f_B);
            ASSERT_GT(r.on_B.force.norm(), 0) << name << " " << what << ": no contact";
            ASSERT_TRUE(!defo_A || f_A.norm() > 0) << name << " " << what << ": no reduced force on A";
            ASSERT_TRUE(!defo_B || f_B.norm() > 0) << name << " " << what << ": no reduced force on B";
            double worst = 0, worst_f = 0;
            for (const Pose& G : Motions()) {
              ReducedVector g_A, g_B;
              const ContactResult m = evaluate(G, &g_A, &g_B);
              const Eigen::Matrix3d R = G.rotation.toRotationMatrix();
              const double scale = r.on_B.force.norm();
              const double torque_scale = std::max(r.on_B.torque.norm(), scale * 0.01);
              worst = std::max({worst, (m.on_B.force - R * r.on_B.force).norm() / scale,
                                (m.on_B.torque - R * r.on_B.torque).norm() / torque_scale});
              if (defo_A) worst_f = std::max(worst_f, (g_A - f_A).norm() / f_A.norm());
              if (defo_B) worst_f = std::max(worst_f, (g_B - f_B).norm() / f_B.norm());
              ASSERT_TRUE(m.on_B.force.allFinite() && m.on_B.torque.allFinite() && g_A.allFinite() && g_B.allFinite());
            }
            std::printf("covariance %s %s: wrench %.3g, reduced forces %.3g (%d contacts)\n", name, what.c_str(), worst,
                        worst_f, r.stats.points_in_contact);
            // Measured: wrench at most 6e-16 (the rigid combinations' values), reduced forces
            // bit-identical: the model works in B's frame, and X_BA = X_WB^-1 X_WA rounds to the
            // same floats under every motion here. Bound as the rigid test's: what float rounding
            // of X_BA could change.
            EXPECT_LT(worst, 1e-6) << name << " " << what;
            EXPECT_LT(worst_f, 1e-6) << name << " " << what;
            worst_wrench = std::max(worst_wrench, worst);
            worst_reduced = std::max(worst_reduced, worst_f);
          }
        }
      }
    }
  }
  std::printf("covariance of the deformable combinations: worst wrench %.3g, worst reduced force %.3g\n", worst_wrench,
              worst_reduced);
}

}  // namespace
}  // namespace contactlab
