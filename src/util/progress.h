// Progress on a terminal for long preprocessing (field builds, repulsion, reduction).
// Prints to stderr only when stderr is a terminal (or CONTACTLAB_PROGRESS=1); thread-safe
// Advance() so TBB workers can report.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace contactlab {

class Progress {
 public:
  Progress(std::string label, std::int64_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void Advance(std::int64_t n = 1);
  void Finish();
  static bool Enabled();

 private:
  void Draw(std::int64_t done, bool final_line);
  std::string label_;
  std::int64_t total_;
  std::atomic<std::int64_t> done_{0};
  std::atomic<std::int64_t> last_drawn_percent_{-1};
  std::chrono::steady_clock::time_point start_;
  bool enabled_;
  bool finished_ = false;
};

}  // namespace contactlab
