// A device that replays a recorded manipulandum trajectory (Barbič & James 2008, sec. 6: "we
// recorded a characteristic manipulandum trajectory"): CSV rows t,x,y,z,qw,qx,qy,qz with
// linear interpolation of position and slerp of orientation between samples.
#pragma once

#include <filesystem>
#include <vector>

#include "haptics/haptic_device.h"

namespace contactlab {

// A recorded trajectory: strictly increasing times (seconds) and poses.
struct RecordedTrajectory {
  std::vector<double> t;     // #samples, seconds
  std::vector<Pose> X_WD;    // #samples
  // The pose at time T (clamped to the recorded span). CURSOR speeds up monotone queries
  // (pass the same variable each time; start at 0). Allocation-free.
  Pose Sample(double t_seconds, std::size_t* cursor) const;
  double duration() const { return t.empty() ? 0.0 : t.back() - t.front(); }
};

// Reads a trajectory CSV (geometry/pose_samples_csv.h: rows t,x,y,z,qw,qx,qy,qz, extra columns
// of a session log ignored). Throws Error "FILE:LINE: what" for bad rows, and when there are none.
RecordedTrajectory ReadTrajectoryCsv(const std::filesystem::path& file);

// Replays a trajectory from the first Read (time 0 = the trajectory's first sample). Written
// wrenches are kept (last_wrench()) but drive nothing. After the end the last pose is held.
class ReplayDevice final : public HapticDevice {
 public:
  // CAPABILITIES: what to report (the replay itself has no limits).
  ReplayDevice(RecordedTrajectory trajectory, const DeviceCapabilities& capabilities);

  std::string_view name() const override { return "replay"; }
  DeviceCapabilities capabilities() const override { return capabilities_; }
  bool Read(std::int64_t now_ns, DeviceState* out) override;
  void Write(const Wrench& wrench, std::int64_t, std::uint32_t) override { last_wrench_ = wrench; }
  void EmergencyZero() noexcept override {}

  bool finished() const { return finished_; }
  const Wrench& last_wrench() const { return last_wrench_; }

 private:
  RecordedTrajectory trajectory_;
  DeviceCapabilities capabilities_;
  bool started_ = false;
  bool finished_ = false;
  std::int64_t t0_ns_ = 0;
  std::size_t cursor_ = 0;
  std::uint64_t sequence_ = 0;
  Wrench last_wrench_;
};

}  // namespace contactlab
