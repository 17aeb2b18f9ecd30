// A body's deformable block (paper sec. 4.1): parsed strictly, built into a reduced model
// from the body's field, cached like fields and pointshells, and sweepable by key path.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "experiment/experiment_config.h"
#include "scene/scene_assets.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// A 20 cm x 2 cm x 2 cm steel-like beam along x, clamped at its x < -0.09 end.
const char* kBeamScene = R"(name: beam
bodies:
  - name: probe
    mesh: "sphere:0.01,3"
    pose: [0.09, 0, 0.025, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 256, levels: 2}
    field: {resolution: 24}
  - name: beam
    mesh: "box:0.1,0.01,0.01,4"
    role: field
    field: {resolution: 64}
    deformable: {model: stvk, modes: 6, cells: 40, E: 2.0e7, nu: 0.3, rho: 1100,
                 damping: {alpha: 0.5, beta: 0.001}, anchor: {below: [x, -0.09]}}
)";

Scene Parse(const std::string& text) { return ParseScene(ConfigNode::LoadString(text, "scene.yaml")); }

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(DeformableBody, TheBlockIsParsedAndARigidBodyHasNone) {
  const Scene s = Parse(kBeamScene);
  EXPECT_FALSE(s.pointshell_body.deformable.has_value());
  ASSERT_TRUE(s.field_body.deformable.has_value());
  const DeformableSpec& d = *s.field_body.deformable;
  EXPECT_EQ(d.kind, ReducedModelKind::kStVK);
  EXPECT_EQ(d.modes, 6);
  EXPECT_EQ(d.cells, 40);
  EXPECT_EQ(d.material.youngs_modulus, 2e7);
  EXPECT_EQ(d.material.poisson_ratio, 0.3);
  EXPECT_EQ(d.material.density, 1100);
  EXPECT_EQ(d.mass_damping, 0.5);
  EXPECT_EQ(d.stiffness_damping, 0.001);
  EXPECT_EQ(d.anchor.kind, Anchoring::Kind::kBelowPlane);
  EXPECT_EQ(d.anchor.normal, Eigen::Vector3d::UnitX());
  EXPECT_EQ(d.anchor.offset, -0.09);
  EXPECT_TRUE(d.implicit_contact);
  EXPECT_FALSE(Parse(Replace(kBeamScene, "anchor: {below", "coupling: explicit, anchor: {below"))
                   .field_body.deformable->implicit_contact);
  EXPECT_NE(ErrorOf(Replace(kBeamScene, "anchor: {below", "coupling: sideways, anchor: {below")).find("coupling"),
            std::string::npos);
  const Scene boxed = Parse(Replace(kBeamScene, "{below: [x, -0.09]}", "{box: [-0.2, -1, -1, -0.09, 1, 1]}"));
  EXPECT_EQ(boxed.field_body.deformable->anchor.kind, Anchoring::Kind::kInBox);
  const Scene ends = Parse(Replace(kBeamScene, "{below: [x, -0.09]}", "{outside: [-0.09, -1, -1, 0.09, 1, 1]}"));
  EXPECT_EQ(ends.field_body.deformable->anchor.kind, Anchoring::Kind::kOutsideBox);
  EXPECT_NE(ErrorOf(Replace(kBeamScene, "{below: [x, -0.09]}", "{below: [x, 0], outside: [0, 0, 0, 1, 1, 1]}"))
                .find("exactly one of below, box and outside"),
            std::string::npos);
  EXPECT_EQ(Parse(Replace(kBeamScene, "{below: [x, -0.09]}", "none")).field_body.deformable->anchor.kind,
            Anchoring::Kind::kFree);
  EXPECT_EQ(Parse(Replace(kBeamScene, "model: stvk", "model: linear")).field_body.deformable->kind,
            ReducedModelKind::kLinear);
}

TEST(DeformableBody, BadValuesNameTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"modes: 6", "modes: 0"},          {"modes: 6", "modes: 41"},     {"cells: 40", "cells: 0"},
      {"E: 2.0e7", "E: -1"},             {"nu: 0.3", "nu: 0.5"},        {"rho: 1100", "rho: 0"},
      {"alpha: 0.5", "alpha: -1"},       {"model: stvk", "model: fem"}, {"[x, -0.09]", "[w, -0.09]"},
      {"[x, -0.09]", "[x]"},             {"modes: 6", "mode: 6"},
  };
  const char* keys[] = {"deformable.modes",  "deformable.modes",        "deformable.cells",
                        "deformable.E",      "deformable.nu",           "deformable.rho",
                        "damping.alpha",     "deformable.model",        "anchor.below[0]",
                        "anchor.below",      "deformable.mode"};
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    const std::string e = ErrorOf(Replace(kBeamScene, cases[i].first, cases[i].second));
    EXPECT_NE(e.find("scene.yaml:"), std::string::npos) << cases[i].second << " -> " << e;
    EXPECT_NE(e.find(keys[i]), std::string::npos) << cases[i].second << " -> " << e;
  }
  const std::string e = ErrorOf(Replace(kBeamScene, "{below: [x, -0.09]}", "{box: [0, 0, 0, -1, 1, 1]}"));
  EXPECT_NE(e.find("anchor.box"), std::string::npos) << e;
}

TEST(DeformableBody, TheReducedModelIsBuiltFromTheFieldCachedAndMatchesBeamTheory) {
  TempDir dir;
  const Scene s = Parse(kBeamScene);
  AssetOptions options{.cache_dir = dir / "cache", .use_cache = true, .verbose = false};
  BodyAssets rigid(s.pointshell_body, options);
  EXPECT_THROW(rigid.reduced_model(), Error);
  BodyAssets beam(s.field_body, options);
  const auto model = beam.reduced_model();
  ASSERT_EQ(model->r(), 6);
  EXPECT_EQ(model->basis.rows(), 3 * model->mesh.num_vertices());
  // The clamp fixes the vertices at x <= -0.09 and only those.
  int fixed = 0;
  for (int v = 0; v < model->mesh.num_vertices(); ++v) {
    EXPECT_EQ(model->fixed[v] != 0, model->mesh.vertices[v].x() <= -0.09) << v;
    fixed += model->fixed[v];
  }
  EXPECT_GT(fixed, 0);
  // Lowest bending frequency against Euler-Bernoulli for a cantilever of free length L:
  // f1 = 1.8751^2 / (2 pi L^2) sqrt(E I / (rho A)), I = a^4 / 12 for a square section of side
  // a. Linear tets on a 2-cell-thick mesh lock in bending, so the model is stiffer: accept
  // up to 2x above, and nothing much below (a softer model would be wrong).
  const Eigen::VectorXd f = ModeFrequencies(*model);
  const double L = 0.19, a = 0.02, E = 2e7, rho = 1100;
  const double f_eb = 1.8751 * 1.8751 / (2 * M_PI * L * L) * std::sqrt(E * a * a / 12 / rho);
  EXPECT_GT(f.minCoeff(), 0.85 * f_eb) << "Euler-Bernoulli " << f_eb << " Hz";
  EXPECT_LT(f.minCoeff(), 2.0 * f_eb) << "Euler-Bernoulli " << f_eb << " Hz";
  // A second body with the same spec reads the cache; another E builds another entry.
  int entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "cache")) {
    entries += e.path().filename().string().rfind("reduced-", 0) == 0 && e.path().extension() != ".key";
  }
  EXPECT_EQ(entries, 1);
  BodyAssets again(s.field_body, options);
  EXPECT_TRUE(again.reduced_model()->basis.isApprox(model->basis));
  BodySpec softer = s.field_body;
  softer.deformable->material.youngs_modulus = 1e7;
  BodyAssets other(softer, options);
  const Eigen::VectorXd f_soft = ModeFrequencies(*other.reduced_model());
  EXPECT_NEAR(f_soft.minCoeff() / f.minCoeff(), std::sqrt(0.5), 0.01);  // f ~ sqrt(E)
  entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "cache")) {
    entries += e.path().filename().string().rfind("reduced-", 0) == 0 && e.path().extension() != ".key";
  }
  EXPECT_EQ(entries, 2);
}

TEST(DeformableBody, DeformableParametersAreSweepableByKeyPath) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kBeamScene;
  std::ofstream(dir / "config.yaml")
      << "name: s\nscene: scene.yaml\nmodels: [pointshell-linear]\n"
         "trajectory: {type: approach-press, direction: [0, 0, -1], depth: 0.001, duration: 0.01}\n"
         "sweep:\n  scene.bodies[name=beam].deformable.modes: [4, 8]\n";
  const std::vector<Job> jobs = ExpandJobs(LoadExperimentConfig(dir / "config.yaml"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].scene.field_body.deformable->modes, 4);
  EXPECT_EQ(jobs[1].scene.field_body.deformable->modes, 8);
  std::ofstream(dir / "config.yaml", std::ios::app) << "  scene.bodies[name=beam].deformable.cells: [0]\n";
  try {
    LoadExperimentConfig(dir / "config.yaml");
    FAIL() << "cells: 0 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("deformable.cells"), std::string::npos) << e.what();
  }
}

// A scene body's dynamics come from its own assets and deformable block: none for a rigid body,
// the block's damping and coupling mode at the cycle asked for, staggered only when both deform;
// a bad cycle is an error naming the body.
TEST(DeformableBody, ItsDynamicsFollowItsBlockAndTheCycle) {
  TempDir dir;
  AssetOptions options;
  options.cache_dir = dir / "cache";
  options.verbose = false;
  std::string text = kBeamScene;
  text.replace(text.find("cells: 40"), 9, "cells: 12");
  text.replace(text.find("anchor:"), 0, "coupling: explicit, ");
  Scene scene = Parse(text);
  SceneAssets assets(scene, options);
  const SceneDynamics one = MakeSceneDynamics(assets, 5e-4);
  EXPECT_EQ(one.A, nullptr);  // the probe is rigid
  ASSERT_NE(one.B, nullptr);
  EXPECT_EQ(one.B->r(), 6);
  EXPECT_EQ(one.B->integrator().options().time_step, 5e-4);
  EXPECT_EQ(one.B->integrator().options().mass_damping, 0.5);
  EXPECT_EQ(one.B->integrator().options().stiffness_damping, 0.001);
  EXPECT_FALSE(one.B->implicit_contact());
  EXPECT_FALSE(one.B->staggered());
  // Both deformable: both staggered.
  Scene both = scene;
  both.pointshell_body = scene.field_body;  // a second beam
  both.pointshell_body.name = "beam2";
  both.pointshell_body.role = "pointshell";
  SceneAssets both_assets(both, options);
  const SceneDynamics two = MakeSceneDynamics(both_assets, 1e-3);
  ASSERT_NE(two.A, nullptr);
  ASSERT_NE(two.B, nullptr);
  EXPECT_TRUE(two.A->staggered());
  EXPECT_TRUE(two.B->staggered());
  try {
    MakeSceneDynamics(assets, 0.0);
    ADD_FAILURE() << "a zero cycle was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("body 'beam'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("time step must be positive"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contactlab
