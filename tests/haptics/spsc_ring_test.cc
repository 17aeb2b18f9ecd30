// Tests of the lock-free SPSC ring that carries haptic cycle records to consumers
// (Barbič & James 2008, sec. 5: the 1 kHz loop must never block on graphics or logging).
#include "haptics/spsc_ring.h"

#include <gtest/gtest.h>

#include <thread>

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
  // 1000 samples: 1..1000 us (as ns + 500), plus one overflow of 7 ms.
  for (int i = 1; i <= 1000; ++i) h.Add(std::int64_t(i) * 1000 + 500);
  h.Add(7000000);
  EXPECT_EQ(h.count(), 1001);
  EXPECT_EQ(h.overflow(), 1);
  EXPECT_NEAR(h.QuantileSeconds(0.5), 501e-6, 1.01e-6);
  EXPECT_NEAR(h.QuantileSeconds(0.99), 991e-6, 1.01e-6);
  EXPECT_DOUBLE_EQ(h.QuantileSeconds(1.0), 7e-3);
  EXPECT_DOUBLE_EQ(h.max_seconds(), 7e-3);
}

}  // namespace
}  // namespace contactlab
