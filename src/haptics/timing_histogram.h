// Fixed-bin histogram of haptic cycle times (Barbič & James 2008, sec. 5: the 1 kHz haptic
// cycle): recording is allocation-free; percentiles are read after the run.
#pragma once

#include <array>
#include <cstdint>

namespace contactlab {

// 1 us bins from 0 to 5 ms; longer samples land in one overflow bin (their maximum is kept).
class TimingHistogram {
 public:
  static constexpr int kBins = 5000;            // bin i holds [i, i+1) microseconds
  static constexpr double kBinSeconds = 1e-6;

  // Adds one sample of DURATION_NS (clamped at 0). Allocation-free, never throws.
  void Add(std::int64_t duration_ns) noexcept;
  void Clear() noexcept;

  std::int64_t count() const { return count_; }
  std::int64_t overflow() const { return bins_[kBins]; }
  double max_seconds() const { return 1e-9 * double(max_ns_); }
  double mean_seconds() const { return count_ ? 1e-9 * double(sum_ns_) / double(count_) : 0.0; }
  // The Q-quantile (Q in [0, 1]) in seconds, resolved to the upper edge of its 1 us bin; the
  // overflow bin reports the maximum. 0 when empty.
  double QuantileSeconds(double q) const;

 private:
  std::array<std::int64_t, kBins + 1> bins_{};
  std::int64_t count_ = 0;
  std::int64_t sum_ns_ = 0;
  std::int64_t max_ns_ = 0;
};

}  // namespace contactlab
