// Simulated time for tests of the real-time haptic loop (haptics/haptic_loop.h): the loop's
// wait for a release jumps the clock to it at once, so cycles run back to back at exact
// multiples of the period, a stall is a jump of the clock (Advance) rather than a sleep, and
// a test can stop the loop at a chosen release (PauseAt) to look at it. The loop thread's CPU
// time is simulated too: it moves only when a cycle works (Work), so a stall (Advance) is a
// cycle that was not running and a Work longer than the period is one that overran. What such a test
// checks then never depends on how the scheduler runs the loop and watchdog threads.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

#include "haptics/haptic_device.h"
#include "haptics/haptic_loop.h"

namespace contactlab::testing {

// Real time a test waits for an event before it gives up: only a hang guard (a broken loop
// fails the test instead of hanging it); a passing test never comes near it.
inline constexpr std::chrono::seconds kHangGuard{60};

class SimulatedLoopClock final : public LoopClock {
 public:
  // START_NS: the simulated time at construction (non-zero: the loop's heartbeat 0 means
  // "not armed").
  explicit SimulatedLoopClock(std::int64_t start_ns = 1'000'000'000) : now_(start_ns) {}

  std::int64_t NowNs() override { return now_.load(); }
  // The simulated CPU time of the loop thread: the sum of its Work calls.
  std::int64_t ThreadCpuNs() override { return cpu_ns_.load(); }

  // Jumps to DEADLINE_NS; before that, waits for Resume() when a pause was set at or before
  // DEADLINE_NS.
  void WaitUntil(std::int64_t deadline_ns, std::int64_t /*spin_ns*/) override {
    std::unique_lock lock(mutex_);
    if (pause_at_ns_ >= 0 && deadline_ns >= pause_at_ns_) {
      pause_at_ns_ = -1;
      paused_ = true;
      changed_.notify_all();
      changed_.wait(lock, [&] { return !paused_; });
    }
    if (deadline_ns > now_.load()) now_.store(deadline_ns);
    changed_.notify_all();
  }

  // The watchdog's poll: returns once the simulated time has moved DURATION_NS on. While the
  // time stands still (the loop paused, or stopped) it returns after a real millisecond, so
  // the watchdog sees its loop stop; what it decides depends only on the simulated time.
  void Sleep(std::int64_t duration_ns) override {
    std::unique_lock lock(mutex_);
    const std::int64_t until = now_.load() + duration_ns;
    changed_.wait_for(lock, std::chrono::milliseconds(1), [&] { return now_.load() >= until; });
    ++polls_;
    polled_.notify_all();
  }

  // How many times Sleep has returned (the watchdog's polls).
  std::int64_t polls() {
    std::lock_guard lock(mutex_);
    return polls_;
  }
  // Blocks until Sleep has returned COUNT times in all; false after kHangGuard of real time.
  bool WaitForPolls(std::int64_t count) {
    std::unique_lock lock(mutex_);
    return polled_.wait_for(lock, kHangGuard, [&] { return polls_ >= count; });
  }

  // Moves the time on by DURATION_NS at once: a cycle that stalls calls this from its model.
  void Advance(std::int64_t duration_ns) {
    std::lock_guard lock(mutex_);
    now_.store(now_.load() + duration_ns);
    changed_.notify_all();
  }

  // Moves the time and the loop thread's CPU time on by DURATION_NS: a cycle that computes for
  // that long without being interrupted calls this from its model.
  void Work(std::int64_t duration_ns) {
    cpu_ns_.fetch_add(duration_ns);
    Advance(duration_ns);
  }

  // The loop will wait, before the first release at or after T_NS, until Resume().
  void PauseAt(std::int64_t t_ns) {
    std::lock_guard lock(mutex_);
    pause_at_ns_ = t_ns;
  }
  // Blocks until the loop waits at the pause; false after kHangGuard of real time.
  bool WaitUntilPaused() {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, kHangGuard, [&] { return paused_; });
  }
  void Resume() {
    std::lock_guard lock(mutex_);
    paused_ = false;
    changed_.notify_all();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::condition_variable polled_;
  std::int64_t polls_ = 0;
  std::atomic<std::int64_t> now_;  // written under mutex_, read without it
  std::atomic<std::int64_t> cpu_ns_{0};
  std::int64_t pause_at_ns_ = -1;
  bool paused_ = false;
};

// A device that forwards to another and counts the emergency zeroes it receives (from the
// loop's watchdog thread), which a test can wait for.
class ZeroCountingDevice final : public HapticDevice {
 public:
  explicit ZeroCountingDevice(HapticDevice& inner) : inner_(inner) {}

  std::string_view name() const override { return inner_.name(); }
  DeviceCapabilities capabilities() const override { return inner_.capabilities(); }
  bool Read(std::int64_t now_ns, DeviceState* out) override { return inner_.Read(now_ns, out); }
  void Write(const Wrench& wrench, std::int64_t now_ns, std::uint32_t safety_flags) override {
    inner_.Write(wrench, now_ns, safety_flags);
  }
  void EmergencyZero() noexcept override {
    inner_.EmergencyZero();
    std::lock_guard lock(mutex_);
    ++zeroes_;
    zeroed_.notify_all();
  }
  DeviceInputStats input_stats() const override { return inner_.input_stats(); }

  int zeroes() {
    std::lock_guard lock(mutex_);
    return zeroes_;
  }
  // Blocks until COUNT emergency zeroes arrived; false after kHangGuard of real time.
  bool WaitForZeroes(int count) {
    std::unique_lock lock(mutex_);
    return zeroed_.wait_for(lock, kHangGuard, [&] { return zeroes_ >= count; });
  }

 private:
  HapticDevice& inner_;
  std::mutex mutex_;
  std::condition_variable zeroed_;
  int zeroes_ = 0;
};

}  // namespace contactlab::testing
