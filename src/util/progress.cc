#include "util/progress.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace contactlab {

bool Progress::Enabled() {
  if (const char* env = std::getenv("CONTACTLAB_PROGRESS")) return std::strcmp(env, "0") != 0;
  return ::isatty(STDERR_FILENO) != 0;
}

Progress::Progress(std::string label, std::int64_t total)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      start_(std::chrono::steady_clock::now()),
      enabled_(Enabled()) {}

Progress::~Progress() { Finish(); }

void Progress::Advance(std::int64_t n) {
  const std::int64_t done = done_.fetch_add(n) + n;
  if (!enabled_) return;
  const std::int64_t percent = done * 100 / total_;
  std::int64_t last = last_drawn_percent_.load();
  if (percent > last && last_drawn_percent_.compare_exchange_strong(last, percent)) {
    Draw(done, false);
  }
}

void Progress::Finish() {
  if (finished_) return;
  finished_ = true;
  if (enabled_) Draw(done_.load(), true);
}

void Progress::Draw(std::int64_t done, bool final_line) {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "\r%s: %3lld%% (%.1f s)%s", label_.c_str(),
               static_cast<long long>(std::min<std::int64_t>(100, done * 100 / total_)), seconds,
               final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace contactlab
