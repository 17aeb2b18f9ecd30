// The haptic cycle with a deformable pointshell body (paper sec. 4.1 and 5): a simulated hand
// pushes a rigid probe (the haptic body) into a clamped beam whose reduced deformation steps at
// the end of every cycle. The cycle allocates nothing, the beam yields to the push (it bends
// away and the force on the hand stays below the rigid beam's), and the deformation settles
// once the hand lets go.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "allocation_counter.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "haptics/haptic_cycle.h"
#include "haptics/haptic_loop.h"
#include "haptics/sim_device.h"
#include "scene_fixtures.h"
#include "test_support.h"

namespace contactlab {
namespace {

constexpr std::int64_t kMs = 1000000;

const std::string kBeam = testing::BeamUnderProbe{}.Yaml();

using testing::CosineRamp;

// Down onto the beam's free end (the probe's bottom 8 mm below the beam's top at the
// deepest), hold, lift.
const testing::PressAndLift kPress{Eigen::Vector3d(0.07, 0, 0.03), 0.018, 0.2, 0.8, 1.6, 2.0};

// Asset options that cache in DIR and print nothing.
AssetOptions QuietCacheIn(const testing::TempDir& dir) {
  AssetOptions options;
  options.cache_dir = dir / "cache";
  options.verbose = false;
  return options;
}

struct PressResult {
  double max_contact_force = 0, max_q = 0, final_q = 0;
  long allocations = 0;
};

// Runs CYCLES cycles of 1 ms: the largest contact force, the deformation's |q| (A's or H's,
// whichever deforms) at its peak and at the end, and the allocations made.
PressResult RunCycles(HapticDevice& device, ContactModel* model, const HapticCycleConfig& config, int cycles) {
  HapticCycle cycle(device, model, config);
  cycle.Start(0);
  PressResult r;
  const long before = testing::AllocationCount();
  for (int i = 1; i <= cycles; ++i) {
    const CycleRecord rec = cycle.Step(i * kMs);
    r.max_contact_force = std::max(
        r.max_contact_force, Eigen::Vector3d(rec.contact_force[0], rec.contact_force[1], rec.contact_force[2]).norm());
    const double q = config.dynamics_B != nullptr ? rec.q_norm_B : rec.q_norm;
    r.max_q = std::max(r.max_q, q);
    r.final_q = q;
  }
  r.allocations = testing::AllocationCount() - before;
  return r;
}

PressResult RunPress(bool deformable) {
  testing::TempDir dir;
  const Scene scene = ParseScene(ConfigNode::LoadString(kBeam, "beam.yaml"));
  const AssetOptions options = QuietCacheIn(dir);
  SceneAssets assets(scene, options);
  Scene rigid_scene = scene;
  rigid_scene.pointshell_body.deformable.reset();
  SceneAssets rigid_assets(rigid_scene, options);
  auto model = deformable ? MakeSceneContactModel("pointshell", scene, assets)
                          : MakeSceneContactModel("pointshell", rigid_scene, rigid_assets);
  SceneDynamics dynamics = MakeSceneDynamics(assets, 1e-3);  // the beam's, rate 1 kHz
  SimDevice device(SimDeviceParams{}, kPress);
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  if (deformable) config.dynamics_A = dynamics.A.get();
  return RunCycles(device, model.get(), config, 3000);
}

TEST(DeformableSession, TheBeamYieldsToTheHandAndTheCycleAllocatesNothing) {
  const PressResult rigid = RunPress(false);
  const PressResult soft = RunPress(true);
  EXPECT_EQ(soft.allocations, 0);
  EXPECT_GT(rigid.max_contact_force, 0.5);
  EXPECT_GT(soft.max_contact_force, 0.1);
  // The yielding beam pushes back less than the rigid one under the same hand motion.
  EXPECT_LT(soft.max_contact_force, 0.9 * rigid.max_contact_force);
  EXPECT_EQ(rigid.max_q, 0);
  EXPECT_GT(soft.max_q, 0);
  EXPECT_TRUE(std::isfinite(soft.final_q));
  EXPECT_LT(soft.final_q, 0.05 * soft.max_q);  // released and damped: back near rest
  std::printf("max contact force: rigid beam %.3f N, deformable beam %.3f N; |q| peak %.4g, final %.4g\n",
              rigid.max_contact_force, soft.max_contact_force, soft.max_q, soft.final_q);
}

// The deformable haptic object (paper sec. 5): the hand holds a free deformable bar (the haptic
// body H, a deformed distance field) and presses its end onto a static sphere. The coupling
// acts on H's rigid pose; H's deformation steps at the end of each cycle.
const char* kHeldBar = R"(name: bar-sphere
bodies:
  - name: sphere
    mesh: "sphere:0.01,2"
    pose: [0.07, 0, 0, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 1024, levels: 3, seed: 1}
    field: {resolution: 32}
  - name: bar
    mesh: "box:0.1,0.01,0.01,4"
    role: field
    field: {resolution: 64}
    deformable: {model: linear, modes: 8, cells: 24, E: 3.0e4, nu: 0.3, rho: 1100,
                 damping: {alpha: 8.0, beta: 0.0005}, field: {proxies: 40, neighbours: 5}}
model: {k_C: 1000, L: 10}
)";

// The bar's end comes down onto the sphere (8 mm past first touch at the deepest), holds, lifts.
const testing::PressAndLift kPressBar{Eigen::Vector3d(0, 0, 0.03), 0.028, 0.2, 0.8, 1.6, 2.0};

PressResult RunHeldBar(bool deformable) {
  testing::TempDir dir;
  Scene scene = ParseScene(ConfigNode::LoadString(kHeldBar, "bar.yaml"));
  if (!deformable) scene.field_body.deformable.reset();
  const AssetOptions options = QuietCacheIn(dir);
  SceneAssets assets(scene, options);
  auto model = MakeSceneContactModel("pointshell", scene, assets);
  SceneDynamics dynamics = MakeSceneDynamics(assets, 1e-3);  // null when rigid
  SimDevice device(SimDeviceParams{}, kPressBar);
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  config.dynamics_B = dynamics.B.get();
  return RunCycles(device, model.get(), config, 3000);
}

TEST(DeformableSession, AHeldDeformableBodyBendsOnContactAndTheCycleAllocatesNothing) {
  const PressResult rigid = RunHeldBar(false);
  const PressResult soft = RunHeldBar(true);
  EXPECT_EQ(soft.allocations, 0);
  EXPECT_GT(rigid.max_contact_force, 0.5);
  EXPECT_GT(soft.max_contact_force, 0.1);
  EXPECT_LT(soft.max_contact_force, 0.9 * rigid.max_contact_force);  // the bar yields
  EXPECT_EQ(rigid.max_q, 0);
  EXPECT_GT(soft.max_q, 0);
  EXPECT_TRUE(std::isfinite(soft.final_q));
  EXPECT_LT(soft.final_q, 0.05 * soft.max_q);  // released and damped: back near rest
  std::printf("held bar: max contact force rigid %.3f N, deformable %.3f N; |q| peak %.4g, final %.4g\n",
              rigid.max_contact_force, soft.max_contact_force, soft.max_q, soft.final_q);
}

// A deformation of the wrong size reaching the cycle (here: dynamics of a beam with fewer modes
// than the one the model was built for) makes the model refuse every query; the cycle applies no
// force, counts each refused query in its record and the session summary, and allocates nothing.
TEST(DeformableSession, ADeformationOfTheWrongSizeIsACountedFaultNotAForce) {
  testing::TempDir dir;
  const Scene scene = ParseScene(ConfigNode::LoadString(kBeam, "beam.yaml"));
  Scene fewer = scene;
  fewer.pointshell_body.deformable->modes = 4;
  const AssetOptions options = QuietCacheIn(dir);
  SceneAssets assets(scene, options), fewer_assets(fewer, options);
  auto model = MakeSceneContactModel("pointshell", scene, assets);
  SceneDynamics wrong = MakeSceneDynamics(fewer_assets, 1e-3);
  ASSERT_EQ(wrong.A->r(), 4);
  ASSERT_EQ(assets.A.reduced_model()->r(), 8);
  SimDevice device(SimDeviceParams{}, kPress);
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  config.dynamics_A = wrong.A.get();
  HapticCycle cycle(device, model.get(), config);
  cycle.Start(0);
  const int cycles = 1000;  // through the deepest press
  double max_force = 0;
  const long before = testing::AllocationCount();
  CycleRecord rec;
  for (int i = 1; i <= cycles; ++i) {
    rec = cycle.Step(i * kMs);
    ASSERT_TRUE(rec.contact_fault) << "cycle " << i;
    max_force = std::max(max_force, std::abs(rec.contact_force[0]) + std::abs(rec.contact_force[1]) +
                                        std::abs(rec.contact_force[2]));
  }
  EXPECT_EQ(testing::AllocationCount() - before, 0);
  EXPECT_EQ(rec.contact_faults, cycles);
  EXPECT_EQ(cycle.contact_faults(), cycles);
  EXPECT_EQ(max_force, 0.0);
  // The session summary reports them.
  HapticLoopReport report;
  report.contact_faults = cycle.contact_faults();
  const std::string text = FormatLoopReport(report);
  EXPECT_NE(text.find("contact faults"), std::string::npos) << text;
  EXPECT_NE(text.find(": 1000\n"), std::string::npos) << text;
  // The same press with the dynamics the model was built for: no fault.
  SceneDynamics right = MakeSceneDynamics(assets, 1e-3);
  config.dynamics_A = right.A.get();
  SimDevice device2(SimDeviceParams{}, kPress);
  HapticCycle good(device2, model.get(), config);
  good.Start(0);
  for (int i = 1; i <= cycles; ++i) good.Step(i * kMs);
  EXPECT_EQ(good.contact_faults(), 0);
}

// A deformation that left finite numbers (a diverged step, injected here mid-press) is not
// queried: that cycle is a counted contact fault with zero force, allocates nothing, and the
// body restarts from rest, so the following cycles render contact again.
TEST(DeformableSession, ANonFiniteDeformationIsACountedFaultWithZeroForce) {
  testing::TempDir dir;
  const Scene scene = ParseScene(ConfigNode::LoadString(kBeam, "beam.yaml"));
  const AssetOptions options = QuietCacheIn(dir);
  SceneAssets assets(scene, options);
  auto model = MakeSceneContactModel("pointshell", scene, assets);
  SceneDynamics dynamics = MakeSceneDynamics(assets, 1e-3);
  SimDevice device(SimDeviceParams{}, kPress);
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  config.dynamics_A = dynamics.A.get();
  HapticCycle cycle(device, model.get(), config);
  cycle.Start(0);
  int i = 1;
  for (; i <= 900; ++i) cycle.Step(i * kMs);  // pressing
  ReducedState diverged(dynamics.A->r());
  diverged.q[1] = std::numeric_limits<double>::infinity();
  diverged.qdot[0] = std::numeric_limits<double>::quiet_NaN();
  dynamics.A->SetState(diverged);
  const long before = testing::AllocationCount();
  const CycleRecord fault = cycle.Step(i++ * kMs);
  EXPECT_EQ(testing::AllocationCount() - before, 0);
  EXPECT_TRUE(fault.contact_fault);
  EXPECT_EQ(fault.contact_faults, 1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(fault.contact_force[k], 0.0) << k;
    EXPECT_TRUE(std::isfinite(fault.device_force[k])) << k;
    EXPECT_TRUE(std::isfinite(fault.device_torque[k])) << k;
  }
  EXPECT_TRUE(dynamics.A->finite());
  EXPECT_TRUE(std::isfinite(fault.q_norm));
  // Back from rest: the press goes on and touches again, with no further fault.
  double force = 0;
  for (int k = 0; k < 50; ++k, ++i) {
    const CycleRecord rec = cycle.Step(i * kMs);
    EXPECT_FALSE(rec.contact_fault) << i;
    force = std::max(force, std::abs(rec.contact_force[2]));
  }
  EXPECT_GT(force, 0.0);
  EXPECT_EQ(cycle.contact_faults(), 1);
}

}  // namespace
}  // namespace contactlab
