// Histogram of haptic cycle times (Barbič & James 2008, sec. 5).
#include "haptics/timing_histogram.h"

#include <algorithm>
#include <cmath>

namespace contactlab {
namespace {

constexpr std::int64_t kFineLimitNs = std::int64_t(TimingHistogram::kFineBins) * 1000;

// Upper edge of bin I, seconds.
double UpperEdgeSeconds(int i) {
  if (i < TimingHistogram::kFineBins) return (i + 1) * TimingHistogram::kBinSeconds;
  const int j = i - TimingHistogram::kFineBins;
  return TimingHistogram::kFineLimitSeconds * std::exp2(double(j + 1) / TimingHistogram::kBinsPerOctave);
}

}  // namespace

void TimingHistogram::Add(std::int64_t duration_ns) noexcept {
  const std::int64_t d = std::max<std::int64_t>(duration_ns, 0);
  std::int64_t bin = d / 1000;
  if (d >= kFineLimitNs) {
    // Logarithmic bins: only for a cycle already 5 ms long, so the log costs nothing that matters.
    const double octaves = std::log2(double(d) / double(kFineLimitNs));
    bin = kFineBins + std::min<std::int64_t>(std::int64_t(octaves * kBinsPerOctave), kBins - kFineBins);
  }
  ++bins_[std::size_t(bin)];
  ++count_;
  sum_ns_ += d;
  max_ns_ = std::max(max_ns_, d);
}

void TimingHistogram::Clear() noexcept {
  bins_.fill(0);
  count_ = sum_ns_ = max_ns_ = 0;
}

std::int64_t TimingHistogram::beyond_fine() const {
  std::int64_t n = 0;
  for (int i = kFineBins; i <= kBins; ++i) n += bins_[std::size_t(i)];
  return n;
}

std::optional<double> TimingHistogram::QuantileSeconds(double q) const {
  if (count_ == 0) return 0.0;
  const std::int64_t rank = std::max<std::int64_t>(1, std::int64_t(std::ceil(std::clamp(q, 0.0, 1.0) * double(count_))));
  std::int64_t seen = 0;
  for (int i = 0; i < kBins; ++i) {
    seen += bins_[std::size_t(i)];
    if (seen >= rank) return std::min(UpperEdgeSeconds(i), max_seconds());
  }
  return std::nullopt;
}

}  // namespace contactlab
