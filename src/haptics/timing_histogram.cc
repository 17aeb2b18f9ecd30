// Fixed-bin histogram of haptic cycle times (Barbič & James 2008, sec. 5).
#include "haptics/timing_histogram.h"

#include <algorithm>
#include <cmath>

namespace contactlab {

void TimingHistogram::Add(std::int64_t duration_ns) noexcept {
  const std::int64_t d = std::max<std::int64_t>(duration_ns, 0);
  const std::int64_t bin = std::min<std::int64_t>(d / 1000, kBins);
  ++bins_[std::size_t(bin)];
  ++count_;
  sum_ns_ += d;
  max_ns_ = std::max(max_ns_, d);
}

void TimingHistogram::Clear() noexcept {
  bins_.fill(0);
  count_ = sum_ns_ = max_ns_ = 0;
}

double TimingHistogram::QuantileSeconds(double q) const {
  if (count_ == 0) return 0.0;
  const std::int64_t rank = std::max<std::int64_t>(1, std::int64_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(count_))));
  std::int64_t seen = 0;
  for (int i = 0; i < kBins; ++i) {
    seen += bins_[std::size_t(i)];
    if (seen >= rank) return std::min((i + 1) * kBinSeconds, max_seconds());
  }
  return max_seconds();
}

}  // namespace contactlab
