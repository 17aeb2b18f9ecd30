// Question: how regular is the real-time haptic loop (Barbič & James 2008, sec. 5: 1 kHz) on
// this machine with a given per-cycle workload? Runs the loop with the sim device for N
// seconds and reports cycle-time percentiles (50, 99, 99.9, max) and deadline misses.
// Quick mode (CONTACTLAB_BENCH_QUICK=1 or --quick): 1 s. --device runs it against another
// backend (e.g. udp:27016 with contactlab-udp-peer).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>

#include "bench_common.h"
#include "haptics/cpu_affinity.h"
#include "haptics/device_factory.h"
#include "haptics/halfspace_contact_model.h"
#include "haptics/haptic_cycle.h"
#include "haptics/haptic_loop.h"
#include "haptics/sim_device.h"
#include "haptics/udp_device.h"
#include "util/finite_options.h"

namespace contactlab {
namespace {

// The halfspace model plus a stand-in for a contact model of known cost: a busy-wait of a fixed
// number of microseconds (fixed wall time), then a fixed amount of arithmetic (OPS steps of one
// dependent multiply-add chain, no memory traffic): the same instructions every cycle, so any
// spread in their CPU time is the machine's, not the work's.
class WorkloadModel final : public ContactModel {
 public:
  WorkloadModel(ContactModel& inner, double busy_us, std::int64_t ops)
      : inner_(inner), busy_ns_(std::int64_t(busy_us * 1e3)), ops_(ops) {}
  std::string_view name() const override { return "workload"; }
  ContactResult Evaluate(const ContactQuery& q) override {
    const std::int64_t until = MonotonicNowNs() + busy_ns_;
    ContactResult r = inner_.Evaluate(q);
    while (MonotonicNowNs() < until) {
    }
    double x = chain_;
    for (std::int64_t k = 0; k < ops_; ++k) x = x * 0.9999999 + 1e-7;
    chain_ = x;  // kept, so the chain is computed
    return r;
  }
  void Reset() override { inner_.Reset(); }

 private:
  ContactModel& inner_;
  std::int64_t busy_ns_;
  std::int64_t ops_;
  double chain_ = 1;
};

}  // namespace
}  // namespace contactlab

int main(int argc, char** argv) {
  using namespace contactlab;
  CLI::App app{"Runs the real-time haptic loop with the sim device and reports cycle-time percentiles"};
  double seconds = 60, workload_us = 100, rate = 1000;
  std::int64_t workload_ops = 0;
  int points_per_edge = 8, cpu = -1;
  bool quick = bench::QuickRun(), no_rt = false;
  std::string device_spec;
  app.add_option("--seconds", seconds, "run time (default 60; 1 in quick mode)")->check(CLI::PositiveNumber);
  app.add_option("--workload-us", workload_us, "busy work per cycle inside the contact model, microseconds")
      ->check(CLI::Range(0.0, 100000.0));
  app.add_option("--workload-ops", workload_ops,
                 "fixed arithmetic per cycle: steps of one dependent multiply-add chain (about 1 ns each), after the busy work")
      ->check(CLI::Range(std::int64_t(0), std::int64_t(100000000)));
  app.add_option("--cpu", cpu, "pin the loop thread to CPU N and keep the record consumer off it")->check(CLI::NonNegativeNumber);
  app.add_option("--points-per-edge", points_per_edge, "halfspace sample points per box edge")->check(CLI::Range(2, 200));
  app.add_option("--rate", rate, "cycle rate, Hz")->check(CLI::Range(1.0, 20000.0));
  app.add_flag("--quick", quick, "1 second run");
  app.add_flag("--no-realtime", no_rt, "do not try SCHED_FIFO / mlockall");
  app.add_option("--device", device_spec, "device spec instead of the sim (e.g. udp:27016, plugin:lib.so; see device_factory.h)");
  RequireFiniteNumbers(app);
  CLI11_PARSE(app, argc, argv);
  if (quick && app.count("--seconds") == 0) seconds = 1.0;

  try {
    // Scene: the sim hand circles 3 cm while pressing a box 5 mm into a halfspace.
    HalfspaceContactModel halfspace(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.02, 0.01), points_per_edge), 1000.0);
    WorkloadModel model(halfspace, workload_us, workload_ops);
    std::unique_ptr<HapticDevice> owned;
    if (device_spec.empty()) {
      owned = std::make_unique<SimDevice>(SimDeviceParams{}, [](double t) {
        return Pose::FromTranslation(
            Eigen::Vector3d(0.03 * std::cos(2 * M_PI * t / 3), 0.03 * std::sin(2 * M_PI * t / 3), 0.005));
      });
    } else {
      owned = MakeDevice(device_spec);
    }
    HapticDevice& device = *owned;
    HapticCycle cycle(device, &model, HapticCycleConfig{});
    HapticLoopOptions opt;
    opt.rate_hz = rate;
    opt.duration_seconds = seconds;
    opt.try_realtime = !no_rt;
    opt.cpu = cpu;
    if (cpu >= 0) KeepThisThreadOffCpu(cpu);  // the consumer below inherits it
    InstallStopSignalHandlers();
    HapticLoop loop(cycle, opt);

    // A consumer thread drains the record ring as a logger would.
    std::atomic<bool> done{false};
    std::int64_t consumed = 0;
    std::thread consumer([&] {
      CycleRecord rec;
      while (!done.load()) {
        while (loop.records().TryPop(&rec)) ++consumed;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      while (loop.records().TryPop(&rec)) ++consumed;
    });
    std::printf("haptic_loop_timing: %.1f s at %.0f Hz, workload %.0f us + %lld ops + %ld halfspace points%s\n",
                seconds, rate, workload_us, (long long)workload_ops, long(halfspace.points().cols()),
                quick ? " (quick)" : "");
    const HapticLoopReport report = loop.Run();
    done.store(true);
    consumer.join();
    std::printf("%s", FormatLoopReport(report).c_str());
    std::printf("  records consumed %lld, dropped %llu\n", (long long)consumed, (unsigned long long)loop.records().dropped());
    if (const auto* sim = dynamic_cast<const SimDevice*>(&device)) {
      std::printf("  device work on the hand %.3e J (includes the force ramp and the spring energy left at the end)\n",
                  sim->energy_into_hand());
    }
    if (const auto* udp = dynamic_cast<const UdpDevice*>(&device)) {
      const UdpStats& u = udp->stats();
      std::printf("  udp: datagrams %lld, accepted %lld, rejected %lld (length %lld, header %lld, checksum %lld, "
                  "duplicate %lld, out of order %lld, stale %lld), wrenches sent %lld\n",
                  (long long)u.datagrams, (long long)u.accepted, (long long)u.rejected(), (long long)u.bad_length,
                  (long long)u.bad_header, (long long)u.bad_checksum, (long long)u.duplicate, (long long)u.out_of_order,
                  (long long)u.stale, (long long)u.wrenches_sent);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: haptic_loop_timing: %s\n", e.what());
    return 1;
  }
}
