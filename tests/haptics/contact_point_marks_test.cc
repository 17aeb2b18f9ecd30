// The live view's per-point contact marks (haptics/contact_point_marks.h): sweeps of chunks
// handed from a writer thread to a reader through the triple buffer, never torn.
#include "haptics/contact_point_marks.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>

#include "util/error.h"

namespace contactlab {
namespace {

// Marks that tell which query wrote them: in contact on odd cycles, clear on even ones.
class CycleParityModel final : public ContactModel {
 public:
  explicit CycleParityModel(bool has_points = true) : has_points_(has_points) {}
  std::string_view name() const override { return "parity"; }
  ContactResult Evaluate(const ContactQuery&) override { return {}; }
  void Reset() override {}
  int PointStates(const ContactQuery& q, std::span<const std::int32_t> points, PointState* out) override {
    if (!has_points_) return 0;
    for (std::size_t k = 0; k < points.size(); ++k) out[k] = q.cycle % 2 ? PointState::kInContact : PointState::kClear;
    return int(points.size());
  }

 private:
  bool has_points_;
};

TEST(ContactPointMarks, ReaderGetsWholeSweepsInOrder) {
  constexpr int kPoints = 50, kChunk = 7;  // a sweep takes 8 cycles, the last one short
  std::vector<std::int32_t> points(kPoints);
  std::iota(points.begin(), points.end(), 0);
  ContactPointMarks marks(points, kChunk);
  CycleParityModel model;
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    ContactQuery q;
    for (std::int64_t cycle = 0; !stop.load(); ++cycle) {
      q.cycle = cycle;
      marks.Update(model, q, cycle);
      std::this_thread::yield();  // on a shared core, let the reader in after every chunk
    }
  });
  PointMarkSweep sweep;
  int sweeps = 0, torn = 0, miscounted = 0, backwards = 0;
  std::uint64_t previous = 0;
  // Reads while the writer writes, until 1000 sweeps were taken. Both threads yield, so that
  // on a loaded machine, where they share a core, a sweep costs a switch and not a time
  // slice; the deadline only guards against a hang (a writer that never publishes).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (sweeps < 1000 && std::chrono::steady_clock::now() < deadline) {
    if (!marks.TakeLatest(&sweep)) {
      std::this_thread::yield();
      continue;
    }
    ++sweeps;
    backwards += sweep.sequence <= previous;
    previous = sweep.sequence;
    // Chunk c of the sweep was written at cycle first_cycle + c.
    int in_contact = 0;
    for (int i = 0; i < kPoints; ++i) {
      const std::int64_t cycle = sweep.first_cycle + i / kChunk;
      torn += sweep.states[i] != (cycle % 2 ? PointState::kInContact : PointState::kClear);
      in_contact += sweep.states[i] == PointState::kInContact;
    }
    miscounted += in_contact != sweep.in_contact || sweep.evaluated != kPoints ||
                  sweep.last_cycle != sweep.first_cycle + (kPoints - 1) / kChunk;
  }
  stop.store(true);
  writer.join();
  EXPECT_EQ(sweeps, 1000);
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(miscounted, 0);
  EXPECT_EQ(backwards, 0);
}

TEST(ContactPointMarks, ModelWithoutPointStatesTurnsMarksOff) {
  ContactPointMarks marks({0, 1, 2}, 2);
  CycleParityModel model(false);
  ContactQuery q;
  for (int cycle = 0; cycle < 4; ++cycle) marks.Update(model, q, cycle);
  EXPECT_FALSE(marks.supported());
  PointMarkSweep sweep;
  EXPECT_FALSE(marks.TakeLatest(&sweep));
  EXPECT_THROW((void)ContactPointMarks({}, 4), Error);
  EXPECT_THROW((void)ContactPointMarks({1}, 0), Error);
}

}  // namespace
}  // namespace contactlab
