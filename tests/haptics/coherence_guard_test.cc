// The haptic cycle guards the contact model's temporal coherence (paper sec. 3.4): the
// coherence lets a culled node sleep for as many cycles as the scene's max_point_speed says
// the bodies need to close its margin. A haptic body that really moves faster would slip into
// sleeping nodes unseen; the cycle measures its motion each cycle (|v| + |w| R) and, above
// max_point_speed, resets the model so that cycle traverses in full.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <vector>

#include "allocation_counter.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "haptics/haptic_cycle.h"
#include "haptics/sim_device.h"
#include "scene_fixtures.h"
#include "test_support.h"

namespace contactlab {
namespace {

constexpr std::int64_t kMs = 1000000;

// A rigid slab (the pointshell body) and a sphere probe (the haptic body); the scene claims
// points move at most 2 cm/s, the hand sweeps the probe along the slab at up to ~1 m/s.
const char* kSlab = R"(name: slab-probe
bodies:
  - name: slab
    mesh: "box:0.1,0.01,0.01,4"
    role: pointshell
    pointshell: {points: 1024, levels: 4, seed: 1}
    field: {resolution: 32}
  - name: probe
    mesh: "sphere:0.01,2"
    pose: [0, 0, 0.03, 1, 0, 0, 0]
    role: field
    field: {resolution: 32}
model: {k_C: 1000, L: 10, max_point_speed: 0.02, coherence: true}
)";

using testing::CosineRamp;

// Down until the probe's bottom is 4 mm into the slab, then back and forth along it.
Pose Sweep(double t) {
  const double z = 0.03 - 0.014 * CosineRamp(t, 0.05, 0.25);
  const double x = 0.06 * std::sin(2 * M_PI * t / 0.4) * CosineRamp(t, 0.25, 0.35);
  return Pose{Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, 0, z)};
}

struct SweepRun {
  std::vector<CycleRecord> records;
  long allocations = 0;
  std::int64_t resets = 0;
};

// COHERENCE: the model's temporal coherence; GUARD: the cycle's speed guard.
// MARKS_CHUNK > 0: the cycle also marks every point of the slab's pointshell, that many a
// cycle, into *MARKS.
SweepRun RunSweep(bool coherence, bool guard, int marks_chunk = 0, std::unique_ptr<ContactPointMarks>* marks = nullptr) {
  testing::TempDir dir;
  Scene scene = ParseScene(ConfigNode::LoadString(kSlab, "slab.yaml"));
  scene.model.coherence = coherence;
  AssetOptions options;
  options.cache_dir = dir / "cache";
  options.verbose = false;
  SceneAssets assets(scene, options);
  auto model = MakeSceneContactModel("pointshell", scene, assets);
  SimDevice device(SimDeviceParams{}, Sweep);
  HapticCycleConfig config;
  config.X_WA = scene.pointshell_body.pose;
  if (guard) {
    config.max_point_speed = scene.model.max_point_speed;
    config.cycle_seconds = scene.model.cycle_seconds;
    config.body_radius_H = assets.B.mesh()->MaxVertexRadius();
  }
  if (marks_chunk > 0) {
    std::vector<std::int32_t> all(std::size_t(assets.A.pointshell()->num_points()));
    std::iota(all.begin(), all.end(), 0);
    *marks = std::make_unique<ContactPointMarks>(all, marks_chunk);
    config.point_marks = marks->get();
  }
  HapticCycle cycle(device, model.get(), config);
  cycle.Start(0);
  SweepRun run;
  run.records.resize(1200);
  const long before = testing::AllocationCount();
  for (int i = 0; i < 1200; ++i) run.records[i] = cycle.Step((i + 1) * kMs);
  run.allocations = testing::AllocationCount() - before;
  run.resets = cycle.coherence_resets();
  return run;
}

// Cycles whose contact differs between A and B (points in contact, or force beyond 1e-9 N).
int Mismatches(const SweepRun& a, const SweepRun& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    const CycleRecord &x = a.records[i], &y = b.records[i];
    double df = 0;
    for (int k = 0; k < 3; ++k) df = std::max(df, std::abs(x.contact_force[k] - y.contact_force[k]));
    if (x.points_in_contact != y.points_in_contact || df > 1e-9) ++n;
  }
  return n;
}

TEST(CoherenceGuard, FastBodyRendersTheSameContactsWithCoherenceOnAsOff) {
  const SweepRun off = RunSweep(false, true);
  const SweepRun guarded = RunSweep(true, true);
  const SweepRun unguarded = RunSweep(true, false);
  int touching = 0;
  double peak_speed = 0;
  for (const CycleRecord& r : guarded.records) {
    touching += r.points_in_contact > 0;
    peak_speed = std::max(peak_speed, r.point_speed);
  }
  std::printf("cycles in contact %d of %zu; peak measured point speed %.3f m/s (max_point_speed 0.02); "
              "coherence resets %lld; cycles differing from coherence off: guarded %d, unguarded %d\n",
              touching, guarded.records.size(), peak_speed, static_cast<long long>(guarded.resets),
              Mismatches(guarded, off), Mismatches(unguarded, off));
  ASSERT_GT(touching, 500);           // the probe really slid along the slab
  ASSERT_GT(peak_speed, 0.1);         // much faster than the scene's bound
  EXPECT_GT(Mismatches(unguarded, off), 0) << "the scenario does not exercise the coherence bound";
  EXPECT_EQ(Mismatches(guarded, off), 0);
  EXPECT_GT(guarded.resets, 0);
  EXPECT_EQ(guarded.records.back().coherence_resets, guarded.resets);
  EXPECT_EQ(guarded.allocations, 0);  // the guard and the reset allocate nothing
}

// The live view's marks (contact_point_marks.h) cost the cycle no allocation, and a sweep made
// in one cycle holds exactly that cycle's points in contact.
TEST(CoherenceGuard, ContactMarksAllocateNothingAndCountTheCyclesContacts) {
  for (int chunk : {4096, 100}) {  // one sweep a cycle; a sweep over 11 cycles
    std::unique_ptr<ContactPointMarks> marks;
    const SweepRun run = RunSweep(true, true, chunk, &marks);
    EXPECT_EQ(run.allocations, 0) << "chunk " << chunk;
    PointMarkSweep sweep;
    ASSERT_TRUE(marks->TakeLatest(&sweep));
    EXPECT_EQ(sweep.states.size(), std::size_t(marks->size()));
    EXPECT_GE(sweep.last_cycle, 1200 - 2 * (marks->size() + chunk - 1) / chunk);
    if (chunk >= marks->size()) {
      ASSERT_EQ(sweep.first_cycle, sweep.last_cycle);
      EXPECT_EQ(sweep.in_contact, run.records[std::size_t(sweep.last_cycle)].points_in_contact);
      EXPECT_GT(sweep.in_contact, 0);
    }
  }
}

}  // namespace
}  // namespace contactlab
