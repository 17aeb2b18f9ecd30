// Histogram of haptic cycle times (Barbič & James 2008, sec. 5: the 1 kHz haptic cycle):
// recording is allocation-free; percentiles are read after the run, off the haptic thread.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

namespace contactlab {

// 1 us bins from 0 to 5 ms, then kBinsPerOctave bins per doubling (each 1.09 % wide) from 5 ms
// to kLimitSeconds (5 ms * 2^16, about 5.5 min); longer samples land in one overflow bin. A slow
// cycle is resolved like any other (to 1.09 % of its length), so percentiles of a session whose
// cycles run long are not all its maximum.
class TimingHistogram {
 public:
  static constexpr int kFineBins = 5000;  // bin i holds [i, i+1) microseconds
  static constexpr double kFineLimitSeconds = 5e-3;
  static constexpr int kBinsPerOctave = 64;
  static constexpr int kOctaves = 16;
  static constexpr int kBins = kFineBins + kBinsPerOctave * kOctaves;  // then the overflow bin
  static constexpr double kLimitSeconds = kFineLimitSeconds * (1 << kOctaves);
  static constexpr double kBinSeconds = 1e-6;
  // Width of a bin beyond kFineLimitSeconds relative to its lower edge: 2^(1/64) - 1.
  static constexpr double kCoarseRelativeWidth = 0.010889286051700475;

  // Adds one sample of DURATION_NS (clamped at 0). Allocation-free, never throws.
  void Add(std::int64_t duration_ns) noexcept;
  void Clear() noexcept;

  std::int64_t count() const { return count_; }
  // Samples longer than kFineLimitSeconds (in the 1.09 % bins or the overflow bin), counted from
  // the bins when read, off the haptic thread.
  std::int64_t beyond_fine() const;
  // Samples longer than kLimitSeconds.
  std::int64_t overflow() const { return bins_[kBins]; }
  double max_seconds() const { return 1e-9 * double(max_ns_); }
  double mean_seconds() const { return count_ ? 1e-9 * double(sum_ns_) / double(count_) : 0.0; }
  // The Q-quantile (Q in [0, 1]) in seconds: the upper edge of its bin, at most the maximum, so
  // within 1 us of the exact order statistic up to 5 ms and within 1.09 % above. nullopt when it
  // lies in the overflow bin (all that is known is that it exceeds kLimitSeconds); 0 when empty.
  std::optional<double> QuantileSeconds(double q) const;

 private:
  std::array<std::int64_t, kBins + 1> bins_{};
  std::int64_t count_ = 0;
  std::int64_t sum_ns_ = 0;
  std::int64_t max_ns_ = 0;
};

}  // namespace contactlab
