// The main of every Google Benchmark program in experiments/: runs the benchmarks the command
// line selects and fails (exit status 1) when any of them reported an error through
// State::SkipWithError — a model that refused its scene, bodies that could not be placed, a
// trajectory too short — so the bench_smoke tests fail on it rather than pass an empty run.
#pragma once

#include <benchmark/benchmark.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace contactlab::bench {

// The display reporter --benchmark_format asks for, which also counts the runs that reported
// an error and keeps their names.
class ErrorCountingReporter final : public benchmark::BenchmarkReporter {
 public:
  ErrorCountingReporter() : display_(benchmark::CreateDefaultDisplayReporter()) {}

  bool ReportContext(const Context& context) override { return display_->ReportContext(context); }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) errors_.push_back(run.benchmark_name() + ": " + run.error_message);
    }
    display_->ReportRuns(runs);
  }
  void Finalize() override { display_->Finalize(); }

  const std::vector<std::string>& errors() const { return errors_; }

 private:
  std::unique_ptr<benchmark::BenchmarkReporter> display_;
  std::vector<std::string> errors_;
};

// Runs the benchmarks selected (after benchmark::Initialize and their registration) and shuts
// the library down. Returns the program's exit status: 0, or 1 when a benchmark reported an
// error (each named on stderr).
inline int RunBenchmarks() {
  ErrorCountingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  for (const std::string& e : reporter.errors()) std::cerr << "benchmark error: " << e << "\n";
  if (reporter.errors().empty()) return 0;
  std::cerr << reporter.errors().size() << " benchmark run(s) reported an error\n";
  return 1;
}

}  // namespace contactlab::bench

// BENCHMARK_MAIN() with RunBenchmarks' exit status.
#define CONTACTLAB_BENCHMARK_MAIN()                                  \
  int main(int argc, char** argv) {                                  \
    benchmark::Initialize(&argc, argv);                              \
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1; \
    return contactlab::bench::RunBenchmarks();                       \
  }
