// The live view of a haptic session (`contactlab session ... --view [PORT]`): an HTTP server on
// the loopback address that serves the viewer page (viewer_page.h) and a server-sent-events
// stream of snapshots of the session: the haptic body's and the device's poses, the forces,
// level rendered and points in contact, cycle time. The haptic thread is untouched: its cycle
// records reach the session's consumer thread through the loop's lock-free ring (haptic_loop.h),
// the consumer stores the newest as a LiveSnapshot (LatestValue, lock-free), and the server's
// threads read it at the stream's rate. With the per-point contact marks of the displayed
// pointshell points (haptics/contact_point_marks.h), the stream also carries the newest
// completed sweep of marks at a lower rate.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "haptics/contact_point_marks.h"
#include "haptics/haptic_cycle.h"
#include "view/latest_value.h"

namespace httplib {
class Server;
}

namespace contactlab {

// One cycle of a session as the page shows it (the session log's quantities, same units).
struct LiveSnapshot {
  double t = 0;                     // seconds since the session's first cycle (the log's t)
  std::int64_t cycle = 0;
  double p_WH[3] = {0, 0, 0};       // haptic body position, m
  double q_WH[4] = {1, 0, 0, 0};    // its orientation (w, x, y, z)
  double p_WD[3] = {0, 0, 0};       // device (manipulandum) position, m
  double q_WD[4] = {1, 0, 0, 0};
  double contact_force[3] = {0, 0, 0};  // on the haptic body, N
  double device_force[3] = {0, 0, 0};   // written to the device, N
  double device_torque[3] = {0, 0, 0};  // N m
  std::int32_t points_in_contact = 0;
  std::int32_t level_rendered = -1;
  double work_us = 0;               // the cycle's time, microseconds
  std::uint32_t safety_flags = 0;
};

// The snapshot of record R of a session whose first cycle started at T0_NS.
LiveSnapshot SnapshotOf(const CycleRecord& r, std::int64_t t0_ns);

// {"t", "cycle", "body": [x,y,z,qw,qx,qy,qz], "device": [...], "contact_force": [...],
// "force": [...], "torque": [...], "contacts", "level", "work_us", "safety"}, numbers with 9
// significant digits (as the session log).
std::string SnapshotJson(const LiveSnapshot& s);

// STATES packed 2 bits a point, 4 points a byte, the first point in the lowest bits (values of
// PointState), the last byte padded with kNotEvaluated.
std::string PackPointStates(const std::vector<PointState>& states);

// {"sequence", "first_cycle", "last_cycle", "points", "in_contact", "evaluated", "states":
// base64 of PackPointStates}.
std::string MarksJson(const PointMarkSweep& sweep);

class LiveViewServer {
 public:
  // Serves PAGE at "/", the snapshots of SOURCE at "/stream" (text/event-stream, one
  // "data: JSON" event whenever a new snapshot is there, checked RATE_HZ times a second) and
  // the newest one at "/snapshot" (JSON; 204 before the first), on 127.0.0.1:PORT (0: a free
  // port). With MARKS, the stream also sends "event: marks" + "data: MarksJson" whenever a
  // newer sweep completed, at most MARKS_RATE_HZ times a second, and "/marks" returns the
  // newest (204 before the first). SOURCE and MARKS must outlive the server. Throws Error
  // naming the address when it cannot bind.
  LiveViewServer(std::string page, const LatestValue<LiveSnapshot>& source, int port, double rate_hz = 50,
                 ContactPointMarks* marks = nullptr, double marks_rate_hz = 15);
  ~LiveViewServer();
  LiveViewServer(const LiveViewServer&) = delete;
  LiveViewServer& operator=(const LiveViewServer&) = delete;

  int port() const { return port_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }
  // Ends every stream and stops serving (also done by the destructor).
  void Stop();

 private:
  std::string page_;
  // The newest sweep of marks and its JSON, shared by the stream threads (TakeLatest has one
  // reader at a time).
  std::pair<std::uint64_t, std::string> LatestMarks();

  const LatestValue<LiveSnapshot>& source_;
  double rate_hz_;
  ContactPointMarks* marks_;
  double marks_rate_hz_;
  std::mutex marks_mutex_;
  PointMarkSweep marks_sweep_;
  std::string marks_json_;
  int port_ = 0;
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  std::atomic<bool> stopping_{false};
};

}  // namespace contactlab
