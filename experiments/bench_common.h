// Shared helpers for the Google Benchmark programs in experiments/.
#pragma once

#include <cstdlib>
#include <cstring>

namespace contactlab::bench {

// True when the program runs as a smoke test (ctest sets CONTACTLAB_BENCH_QUICK=1): use
// small inputs so the run takes seconds.
inline bool QuickRun() {
  const char* v = std::getenv("CONTACTLAB_BENCH_QUICK");
  return v != nullptr && std::strcmp(v, "0") != 0;
}

}  // namespace contactlab::bench
