// Tests of the lock-free SPSC ring that carries haptic cycle records to consumers
// (Barbič & James 2008, sec. 5: the 1 kHz loop must never block on graphics or logging).
#include "haptics/spsc_ring.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "haptics/haptic_loop.h"
#include "haptics/timing_histogram.h"

namespace contactlab {
namespace {

struct Item {
  std::uint64_t seq;
  std::uint64_t check;  // a function of seq: detects torn or stale copies
};

TEST(SpscRing, TwoThreadsSeeEveryItemOnceInOrder) {
  static SpscRing<Item, 64> ring;  // small: the producer often finds it full
  constexpr std::uint64_t kN = 200000;
  std::thread producer([] {
    for (std::uint64_t i = 0; i < kN;) {
      if (ring.TryPush(Item{i, i * 0x9E3779B97F4A7C15ULL})) {
        ++i;
      } else {
        std::this_thread::yield();  // full: let the consumer run (the machine may have one free core)
      }
    }
  });
  // The consumer starts once the producer has found the ring full (it cannot but fill it while
  // nothing is popped), so a full ring is met whatever the scheduler does; from then on the
  // two run freely.
  while (ring.dropped() == 0) std::this_thread::yield();
  std::uint64_t expected = 0, bad = 0;
  Item it;
  while (expected < kN) {
    if (ring.TryPop(&it)) {
      if (it.seq != expected || it.check != it.seq * 0x9E3779B97F4A7C15ULL) ++bad;
      ++expected;
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_EQ(bad, 0u);
  EXPECT_FALSE(ring.TryPop(&it));
  EXPECT_GT(ring.dropped(), 0u);  // failed pushes were counted (and retried by this producer)
}

TEST(SpscRing, FullRingRefusesAndCountsDrops) {
  SpscRing<int, 4> ring;
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(ring.TryPush(i));
  EXPECT_FALSE(ring.TryPush(99));
  EXPECT_EQ(ring.dropped(), 1u);
  EXPECT_EQ(ring.SizeApprox(), 4u);
  int v;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(ring.TryPop(&v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(ring.TryPop(&v));
}

TEST(TimingHistogram, QuantilesMatchSortedSamplesToOneMicrosecond) {
  TimingHistogram h;
  // 1000 samples: 1..1000 us (as ns + 500), plus one of 7 ms, past the 1 us bins.
  for (int i = 1; i <= 1000; ++i) h.Add(std::int64_t(i) * 1000 + 500);
  h.Add(7000000);
  EXPECT_EQ(h.count(), 1001);
  EXPECT_EQ(h.beyond_fine(), 1);
  EXPECT_EQ(h.overflow(), 0);
  EXPECT_NEAR(*h.QuantileSeconds(0.5), 501e-6, 1.01e-6);
  EXPECT_NEAR(*h.QuantileSeconds(0.99), 991e-6, 1.01e-6);
  EXPECT_DOUBLE_EQ(*h.QuantileSeconds(1.0), 7e-3);
  EXPECT_DOUBLE_EQ(h.max_seconds(), 7e-3);
}

// The exact order statistic of SAMPLES (ns) for quantile Q: the ceil(Q n)-th smallest, seconds.
double ExactQuantileSeconds(std::vector<std::int64_t> samples, double q) {
  std::sort(samples.begin(), samples.end());
  const std::size_t rank = std::max<std::size_t>(1, std::size_t(std::ceil(q * double(samples.size()))));
  return 1e-9 * double(samples[rank - 1]);
}

// A session whose slow cycles exceeded the 5 ms of 1 us bins printed p99 and p99.9 both as the
// maximum: every sample past 5 ms sat in one overflow bin. Now they are resolved to 1.09 %: each
// percentile lies within that of the exact order statistic of the samples, never below it.
TEST(TimingHistogram, PercentilesOfCyclesLongerThanFiveMillisecondsAreResolvedNotTheMaximum) {
  std::vector<std::int64_t> samples;
  std::uint64_t state = 12345;
  const auto uniform = [&] {  // a fixed linear congruential sequence in [0, 1)
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  };
  for (int i = 0; i < 9000; ++i) samples.push_back(std::int64_t(50e3 + 400e3 * uniform()));  // 50-450 us
  for (int i = 0; i < 1000; ++i) samples.push_back(std::int64_t(6e6 * std::pow(40.0, uniform())));  // 6-240 ms
  TimingHistogram h;
  for (const std::int64_t s : samples) h.Add(s);
  EXPECT_EQ(h.beyond_fine(), 1000);
  EXPECT_EQ(h.overflow(), 0);
  for (const double q : {0.5, 0.9, 0.95, 0.99, 0.999, 1.0}) {
    const double exact = ExactQuantileSeconds(samples, q);
    const std::optional<double> got = h.QuantileSeconds(q);
    ASSERT_TRUE(got.has_value()) << q;
    EXPECT_GE(*got, exact) << q;
    EXPECT_LE(*got, exact < 5e-3 ? exact + 1e-6 : exact * (1 + TimingHistogram::kCoarseRelativeWidth)) << q;
  }
  EXPECT_LT(*h.QuantileSeconds(0.99), 0.9 * h.max_seconds());
  EXPECT_LT(*h.QuantileSeconds(0.99), *h.QuantileSeconds(0.999));
}

// Past the histogram's range (kLimitSeconds, 5.5 min) a percentile is unknown, not the maximum,
// and the report says how many samples lie past 5 ms and past the range instead of printing
// numbers it does not have.
TEST(TimingHistogram, SamplesPastTheRangeAreCountedAndTheirPercentilesAreNotInvented) {
  TimingHistogram h;
  for (int i = 0; i < 990; ++i) h.Add(100000);          // 100 us
  for (int i = 0; i < 8; ++i) h.Add(20000000);          // 20 ms
  for (int i = 0; i < 2; ++i) h.Add(400000000000);      // 400 s, past the range
  EXPECT_EQ(h.overflow(), 2);
  EXPECT_EQ(h.beyond_fine(), 10);
  EXPECT_NEAR(*h.QuantileSeconds(0.99), 101e-6, 1e-12);
  EXPECT_NEAR(*h.QuantileSeconds(0.995), 20e-3, 20e-3 * TimingHistogram::kCoarseRelativeWidth);
  EXPECT_FALSE(h.QuantileSeconds(0.999).has_value());
  const std::string line = FormatTimingHistogram("work", h);
  EXPECT_NE(line.find("p99 101 "), std::string::npos) << line;
  EXPECT_NE(line.find("p99.9 >327680000 "), std::string::npos) << line;
  EXPECT_NE(line.find("max 4e+08"), std::string::npos) << line;
  EXPECT_NE(line.find("over 5000 us: 10, resolved to 1.1 %"), std::string::npos) << line;
  EXPECT_NE(line.find("over 327680000 us: 2, not resolved"), std::string::npos) << line;
  // Within 5 ms the line says nothing more than before.
  TimingHistogram fast;
  fast.Add(100000);
  EXPECT_EQ(FormatTimingHistogram("work", fast), "  work us: p50 100  p99 100  p99.9 100  max 100  (n 1)\n");
}

}  // namespace
}  // namespace contactlab
