// Question: what does one haptic cycle cost outside the contact model — the static virtual
// coupling solve of eqs. (5)-(6) (Barbič & James 2008, sec. 5) plus the safety filter — and
// how does a full simulated cycle (sim device + halfspace contact + coupling + safety) scale
// with the number of contact sample points?
#include <benchmark/benchmark.h>

#include <random>

#include "bench_common.h"
#include "bench_main.h"
#include "haptics/halfspace_contact_model.h"
#include "haptics/haptic_cycle.h"
#include "haptics/safety_filter.h"
#include "haptics/sim_device.h"
#include "haptics/virtual_coupling.h"

namespace contactlab {
namespace {

// A fixed pool of random, well-conditioned contact systems so the solve sees varied inputs.
struct ContactSystems {
  std::vector<Matrix6d> K;
  std::vector<Wrench> w;
  std::vector<Pose> X_WD;
  explicit ContactSystems(int n) {
    std::mt19937 rng(1);
    std::normal_distribution<double> g(0, 1);
    for (int i = 0; i < n; ++i) {
      Matrix6d k;
      for (int j = 0; j < 36; ++j) k(j / 6, j % 6) = 50.0 * g(rng);
      K.push_back(k - 3000.0 * Matrix6d::Identity());
      Wrench ww;
      ww.force = Eigen::Vector3d(g(rng), g(rng), g(rng));
      ww.torque = 0.05 * Eigen::Vector3d(g(rng), g(rng), g(rng));
      w.push_back(ww);
      X_WD.push_back(Pose{Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * g(rng), Eigen::Vector3d::UnitX())),
                          0.002 * Eigen::Vector3d(g(rng), g(rng), g(rng))});
    }
  }
};

void BM_CouplingSolve(benchmark::State& state) {
  const ContactSystems sys(256);
  StaticVirtualCoupling vc(VirtualCouplingParams{});
  std::size_t i = 0;
  for (auto _ : state) {
    const CouplingStep st = vc.Update(sys.X_WD[i], sys.w[i], sys.K[i]);
    benchmark::DoNotOptimize(st);
    i = (i + 1) & 255;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CouplingSolve)->Unit(benchmark::kMicrosecond);

void BM_CouplingSolvePlusSafety(benchmark::State& state) {
  const ContactSystems sys(256);
  StaticVirtualCoupling vc(VirtualCouplingParams{});
  SafetyParams sp;
  sp.max_force = 8;
  sp.max_torque = 0.5;
  SafetyFilter safety(sp);
  safety.Start(0);
  std::size_t i = 0;
  std::int64_t t = 0;
  for (auto _ : state) {
    t += 1000000;
    const CouplingStep st = vc.Update(sys.X_WD[i], sys.w[i], sys.K[i]);
    const Wrench out = safety.Filter(st.to_device, t, t);
    benchmark::DoNotOptimize(out);
    i = (i + 1) & 255;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CouplingSolvePlusSafety)->Unit(benchmark::kMicrosecond);

void BM_SafetyFilterOnly(benchmark::State& state) {
  SafetyParams sp;
  sp.max_force = 8;
  sp.max_torque = 0.5;
  SafetyFilter safety(sp);
  safety.Start(0);
  Wrench w;
  w.force = Eigen::Vector3d(3, 9, -1);
  w.torque = Eigen::Vector3d(0.1, 0.7, 0);
  std::int64_t t = 0;
  for (auto _ : state) {
    t += 1000000;
    benchmark::DoNotOptimize(safety.Filter(w, t, t));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SafetyFilterOnly)->Unit(benchmark::kMicrosecond);

// range(0): samples per box edge n (6 n^2 - 12 n + 8 points); the box rests pressed on the plane.
void BM_FullSimulatedCycle(benchmark::State& state) {
  const int n = int(state.range(0));
  HalfspaceContactModel model(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), n), 1000.0);
  SimDevice device(SimDeviceParams{}, [](double) { return Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.006)); });
  HapticCycle cycle(device, &model, HapticCycleConfig{});
  cycle.Start(0);
  std::int64_t t = 0;
  for (auto _ : state) {
    t += 1000000;
    benchmark::DoNotOptimize(cycle.Step(t));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["points"] = double(model.points().cols());
}
BENCHMARK(BM_FullSimulatedCycle)
    ->Unit(benchmark::kMicrosecond)
    ->Arg(4)    // 56 points: a coarse box
    ->Arg(16)   // 1352 points
    ->Arg(64);  // 24200 points: a dense pointshell-sized set (skipped in quick mode)

}  // namespace
}  // namespace contactlab

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (contactlab::bench::QuickRun()) {
    // Smoke run: the dense point set is left out.
    benchmark::SetBenchmarkFilter("^(BM_Coupling|BM_Safety|BM_FullSimulatedCycle/(4|16)$)");
  }
  return contactlab::bench::RunBenchmarks();
}
