// Frame covariance of every registered contact model (issue 15): turning and moving the whole
// scene — both bodies by one rigid motion G of the world — turns the wrench on B with it:
// F' = R_G F and, about B's moved origin, τ' = R_G τ. Nothing about contact depends on where
// the world's axes are, so a model that breaks this has a preferred direction (an axis-aligned
// step, a world-frame tolerance). Three contacts (ball on a plate, crossed bars, a cube's corner
// into a block), each under three motions, both role orders.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "baselines/register_baselines.h"
#include "contact/model_registry.h"
#include "experiment/scene.h"
#include "experiment/scene_assets.h"
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

std::string SceneText(const Contact& c) {
  std::string s = std::string("name: covariance\nbodies:\n") +
                  "  - {name: a, mesh: \"" + c.mesh_A + "\", role: pointshell, pointshell: {points: 2048, levels: 3},"
                  " field: {resolution: 48}}\n" +
                  "  - {name: b, mesh: \"" + c.mesh_B + "\", role: field, pointshell: {points: 2048, levels: 3},"
                  " field: {resolution: 48}}\n" +
                  "model: {k_C: 1000, L: 10, coherence: false}\n";
  return s;
}

Pose Turned(const Eigen::Vector3d& w, const Eigen::Vector3d& t) { return {RotationFromVector(w), t}; }

TEST(FrameCovariance, EveryModelTurnsItsWrenchWithTheScene) {
  RegisterBaselineContactModels();
  testing::TempDir cache;
  AssetOptions options;
  options.cache_dir = cache.path();
  options.verbose = false;
  const double e = 0.004 * std::sqrt(2.0);
  const std::vector<Contact> contacts = {
      {"ball-on-plate", "sphere:0.01,3", "box:0.03,0.03,0.005,3", Turned({0.2, 0.1, -0.3}, {0.001, -0.002, 0.0135}),
       Pose::Identity()},
      {"crossed-bars", "box:0.02,0.004,0.004,3", "box:0.004,0.02,0.004,3",
       Turned({M_PI / 4, 0, 0}, {0.0004, -0.0003, 2 * e - 0.001}), Turned({0, M_PI / 4, 0}, {0, 0, 0})},
      {"corner-into-block", "box:0.01,0.01,0.01,3", "box:0.03,0.03,0.01,3",
       Pose{Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(-1, -1, -1).normalized(), -Eigen::Vector3d::UnitZ()),
            Eigen::Vector3d(0.0002, 0.0001, 0.01 + 0.01 * std::sqrt(3.0) - 0.002)},
       Pose::Identity()},
  };
  const std::vector<Pose> motions = {Turned({0, 0, 1.1}, {0.3, -0.2, 0.1}), Turned({0.7, -0.4, 0.9}, {0, 0, 0}),
                                     Turned({-2.0, 0.5, 0.3}, {-1.0, 2.0, 0.5})};
  for (const Contact& c : contacts) {
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
        ASSERT_GT(r.on_B.force.norm(), 0) << name << " " << c.name << " order " << order << ": no contact";
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
}

}  // namespace
}  // namespace contactlab
