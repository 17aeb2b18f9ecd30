// The haptic closed loop (Barbič & James 2008, sec. 5) with the paper's contact model on a real
// scene, knight-screwdriver: the simulated hand pushes the knight (the haptic body) into the
// screwdriver, slides it along, and pushes a tilted knight hard against it, through static
// virtual coupling at k_VC = 1000 N/m (between a Touch and an omega). The loop must be passive
// (the device puts no more energy into the hand than 1 % of the largest energy the coupling
// spring stored) and the still hold in contact must settle (H still to 20 µm RMS, force ripple
// below 0.05 N RMS, and no larger at the end of the hold than at its start). A control shows
// the observer catches a model that pumps energy. The sweep over models and k_VC is
// experiments/closed-loop-stability.yaml (study: closed-loop).
//
// The scene's pointshell is cut to 4096 points and its fields to 64^3 so the assets build in
// a few seconds in a fresh cache; the closed loop is the same.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "experiment/studies/closed_loop/closed_loop_stability.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

struct KnightScrewdriver {
  explicit KnightScrewdriver(const testing::TempDir& cache)
      : scene(Load()), assets(scene, Options(cache)), where(MakeClosedLoopScene(scene, assets)) {}
  static Scene Load() {
    Scene s = LoadScene(RequireDataFile("scenes/knight-screwdriver.yaml"));
    s.pointshell_body.pointshell.points = 4096;
    s.pointshell_body.pointshell.levels = 3;
    s.pointshell_body.field.resolution = 64;
    s.field_body.field.resolution = 64;
    return s;
  }
  static AssetOptions Options(const testing::TempDir& cache) {
    AssetOptions o;
    o.cache_dir = cache.path();
    o.verbose = false;
    return o;
  }
  Scene scene;
  SceneAssets assets;
  ClosedLoopScene where;
};

void Print(const char* what, const ClosedLoopMetrics& m) {
  std::printf("%-7s energy into hand %+.3e J (peak stored %.3e J); hold H rms %.2e -> %.2e m, force rms %.2e -> %.2e N, "
              "mean %.2f N; max contact %.2f N, points %d, clamps %lld\n",
              what, m.energy_into_hand, m.peak_stored_energy, m.early_position_rms, m.late_position_rms,
              m.early_force_rms, m.late_force_rms, m.hold_force_mean, m.max_contact_force, m.max_points_in_contact,
              static_cast<long long>(m.clamped_cycles));
}

// The scene's model.node_budget reaches every cycle of the loop (scene/scene_query.h
// SceneCycleConfig, which MakeClosedLoopScene and the closed-loop study use): with a budget far
// below what the press visits, the paper's model degrades to a coarser level, so fewer points
// are ever in contact than without one. Before, the loop dropped the scene's budget and the two
// runs were identical.
TEST(ClosedLoopScene, NodeBudgetOfTheSceneReachesEveryCycle) {
  testing::TempDir cache;
  KnightScrewdriver s(cache);
  ClosedLoopCase c;
  c.motion = LoopMotion::kPush;
  c.k_vc = 1000;
  auto unlimited = MakeSceneContactModel("pointshell", s.scene, s.assets);
  const ClosedLoopMetrics full = RunClosedLoop(*unlimited, s.where, c);
  Scene budgeted = s.scene;
  budgeted.node_budget = 8;
  const ClosedLoopScene where = MakeClosedLoopScene(budgeted, s.assets);
  EXPECT_EQ(where.cycle.node_budget, 8);
  auto model = MakeSceneContactModel("pointshell", budgeted, s.assets);
  const ClosedLoopMetrics cut = RunClosedLoop(*model, where, c);
  Print("full", full);
  Print("budget", cut);
  EXPECT_GT(full.max_points_in_contact, 0);
  EXPECT_LT(cut.max_points_in_contact, full.max_points_in_contact);
}

TEST(ClosedLoopScene, PaperModelIsPassiveAndSettlesOnKnightScrewdriverAtModerateStiffness) {
  testing::TempDir cache;
  KnightScrewdriver s(cache);
  auto model = MakeSceneContactModel("pointshell", s.scene, s.assets);
  for (LoopMotion motion : {LoopMotion::kPush, LoopMotion::kSlide, LoopMotion::kCorner}) {
    SCOPED_TRACE(LoopMotionName(motion));
    ClosedLoopCase c;
    c.motion = motion;
    c.k_vc = 1000;
    const ClosedLoopMetrics m = RunClosedLoop(*model, s.where, c);
    Print(LoopMotionName(motion), m);
    // It really was contact: pressed during the hold, not free space.
    EXPECT_GT(m.max_contact_force, 0.5);
    EXPECT_GT(m.hold_force_mean, 0.3);
    // No faults.
    EXPECT_TRUE(m.finite);
    EXPECT_EQ(m.non_finite_cycles, 0);
    EXPECT_EQ(m.solve_failures, 0);
    // Passive: at most 1 % of the peak stored coupling energy (or 1 µJ) generated over the run.
    EXPECT_LE(m.energy_into_hand, std::max(1e-6, 0.01 * m.peak_stored_energy));
    // The oscillation decays: small at the end of the hold, and no larger than at its start.
    EXPECT_LT(m.late_position_rms, 20e-6);
    EXPECT_LT(m.late_force_rms, 0.05);
    EXPECT_LE(m.late_force_rms, m.early_force_rms + 1e-3);
    EXPECT_TRUE(m.stable());
  }
}

// The loop runs at the scene's rate: at 10 kHz the same push takes ten times the cycles, ends
// pressed as hard (the hold's force is the quasi-static balance of the hand and the coupling,
// whatever the rate), stays passive and settles (the coupling's damping has the paper's time
// constant at any rate), and the force changes by less from one cycle to the next: the contact
// comes on over ten times as many cycles.
TEST(ClosedLoopScene, TheLoopRunsAtTheScenesRate) {
  testing::TempDir cache;
  KnightScrewdriver s(cache);
  ClosedLoopCase c;
  c.motion = LoopMotion::kPush;
  c.k_vc = 1000;
  auto at_1k = MakeSceneContactModel("pointshell", s.scene, s.assets);
  const ClosedLoopMetrics slow = RunClosedLoop(*at_1k, s.where, c);
  s.scene.model.cycle_seconds = 1e-4;
  ClosedLoopScene fast_where = s.where;
  fast_where.cycle.cycle_seconds = 1e-4;
  auto at_10k = MakeSceneContactModel("pointshell", s.scene, s.assets);
  const ClosedLoopMetrics fast = RunClosedLoop(*at_10k, fast_where, c);
  Print("1 kHz", slow);
  Print("10 kHz", fast);
  std::printf("largest force jump per cycle: %.4f N at 1 kHz, %.4f N at 10 kHz\n", slow.max_force_jump,
              fast.max_force_jump);
  EXPECT_DOUBLE_EQ(slow.rate_hz, 1000.0);
  EXPECT_DOUBLE_EQ(fast.rate_hz, 10000.0);
  EXPECT_EQ(fast.cycles, 10 * slow.cycles);
  EXPECT_TRUE(slow.stable());
  EXPECT_TRUE(fast.stable());
  EXPECT_NEAR(fast.hold_force_mean, slow.hold_force_mean, 0.05 * slow.hold_force_mean);
  EXPECT_GT(slow.max_force_jump, 0.0);
  EXPECT_LT(fast.max_force_jump, 0.25 * slow.max_force_jump);
}

// A contact model that pumps energy: the paper's force plus a negative damping force on H along
// its own velocity (what a delayed or mis-signed contact force does). The observer must see it.
class EnergyPump final : public ContactModel {
 public:
  EnergyPump(ContactModel& inner, double gain) : inner_(inner), gain_(gain) {}
  std::string_view name() const override { return "energy-pump"; }
  ContactResult Evaluate(const ContactQuery& q) override {
    ContactResult r = inner_.Evaluate(q);
    if (have_last_ && r.stats.points_in_contact > 0) {
      r.on_B.force += gain_ * (q.X_WB.translation - last_) / 1e-3;
    }
    last_ = q.X_WB.translation;
    have_last_ = true;
    return r;
  }
  void Reset() override {
    inner_.Reset();
    have_last_ = false;
  }

 private:
  ContactModel& inner_;
  double gain_;
  Eigen::Vector3d last_ = Eigen::Vector3d::Zero();
  bool have_last_ = false;
};

TEST(ClosedLoopScene, TheObserverFlagsAModelThatPumpsEnergy) {
  testing::TempDir cache;
  KnightScrewdriver s(cache);
  auto inner = MakeSceneContactModel("pointshell", s.scene, s.assets);
  EnergyPump pump(*inner, 20.0);  // N s/m of negative damping while in contact
  ClosedLoopCase c;
  c.motion = LoopMotion::kSlide;
  c.k_vc = 1000;
  const ClosedLoopMetrics m = RunClosedLoop(pump, s.where, c);
  Print("pump", m);
  EXPECT_FALSE(m.passive());
  EXPECT_FALSE(m.settled());
  EXPECT_FALSE(m.stable());
}

// The study steps a deformable body through the scene's own dynamics: the hand pushes a rigid
// probe onto a clamped beam that bends (its coordinates move off rest) and pushes back less than
// the same beam held rigid; dynamics of the wrong size make every query a counted fault and the
// run unstable.
TEST(ClosedLoopScene, TheStudyStepsADeformableBodyAndCountsRefusedQueries) {
  testing::TempDir cache;
  const std::string kBeam = testing::BeamUnderProbe{
      .points = 1024, .beam_resolution = 48, .modes = 6, .cells = 16, .E = 2.0e6, .probe_z = 0.04}.Yaml();
  const Scene scene = ParseScene(ConfigNode::LoadString(kBeam, "beam.yaml"));
  SceneAssets assets(scene, KnightScrewdriver::Options(cache));
  const ClosedLoopScene where = MakeClosedLoopScene(scene, assets);
  auto model = MakeSceneContactModel("pointshell", scene, assets);
  ClosedLoopCase c;
  c.push_depth = 0.004;
  SceneDynamics dynamics = MakeSceneDynamics(assets, where.cycle.cycle_seconds);
  ASSERT_NE(dynamics.A, nullptr);
  const ClosedLoopMetrics soft = RunClosedLoop(*model, where, c, &dynamics);
  const ClosedLoopMetrics held = RunClosedLoop(*model, where, c);  // no dynamics: the beam stays at rest
  Print("soft", soft);
  Print("held", held);
  EXPECT_GT(soft.max_q_norm, 0);
  EXPECT_EQ(held.max_q_norm, 0);
  EXPECT_EQ(soft.contact_faults, 0);
  EXPECT_TRUE(soft.finite);
  EXPECT_GT(held.max_contact_force, 0.3);
  EXPECT_LT(soft.max_contact_force, held.max_contact_force);
  // Dynamics of a beam with fewer modes than the model's: every query refused.
  Scene fewer = scene;
  fewer.pointshell_body.deformable->modes = 4;
  SceneAssets fewer_assets(fewer, KnightScrewdriver::Options(cache));
  SceneDynamics wrong = MakeSceneDynamics(fewer_assets, where.cycle.cycle_seconds);
  const ClosedLoopMetrics refused = RunClosedLoop(*model, where, c, &wrong);
  EXPECT_EQ(refused.contact_faults, refused.cycles);
  EXPECT_EQ(refused.max_contact_force, 0.0);
  EXPECT_FALSE(refused.stable());
}

}  // namespace
}  // namespace contactlab
