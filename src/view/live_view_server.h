// The live view of a haptic session (`contactlab session ... --view [PORT]`): an HTTP server on the
// loopback address that serves the viewer page and the scripts it loads (viewer_page.h,
// ServedViewerPage) and a server-sent-events stream of snapshots of the session: the haptic body's
// and the device's poses, the forces, level rendered and points in contact, cycle time. The haptic
// thread is untouched: its cycle records reach the session's consumer thread through the loop's
// lock-free ring (haptic_loop.h), the consumer takes one snapshot every so many cycles
// (LiveSnapshotPublisher: by session time, not by the wall clock) into a lock-free history
// (snapshot_history.h), and each stream sends every snapshot of the history in order from where it
// joined, whenever its thread runs. With the per-point contact marks of the displayed pointshell
// points (haptics/contact_point_marks.h), the stream also carries the newest completed sweep of
// marks, at most one per so many cycles.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "haptics/contact_point_marks.h"
#include "scene/pair_contact_marks.h"
#include "haptics/haptic_cycle.h"
#include "view/snapshot_history.h"
#include "view/viewer_page.h"

namespace httplib {
class DataSink;
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
  bool has_proxy = false;           // the model's proxy of the haptic body (pointshell-ccd)
  double p_WP[3] = {0, 0, 0};
  double q_WP[4] = {1, 0, 0, 0};
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

// A session's snapshots in the order they were taken, for the streams: 256 of them, 5 s at 50
// a second (a stream that falls further behind skips to the newest).
using LiveSnapshotHistory = SnapshotHistory<LiveSnapshot, 256>;

// Which of a session's records become snapshots, decided in session time: the first record of
// every block of EVERY_CYCLES haptic cycles, i.e. cycles 0, N, 2N, ... when the consumer
// dropped none (at 1 kHz and N = 20: 50 snapshots a second of session time, however fast or
// late the consumer and the streams run).
class LiveSnapshotPublisher {
 public:
  // HISTORY must outlive the publisher. Throws Error unless EVERY_CYCLES > 0.
  LiveSnapshotPublisher(LiveSnapshotHistory& history, std::int64_t every_cycles);
  // Consumer thread, each record in order; T0_NS is the first record's time. Publishes R when
  // it opens a new block. Wait-free, allocation-free, never throws.
  void Offer(const CycleRecord& r, std::int64_t t0_ns) noexcept {
    const std::int64_t block = r.cycle / every_cycles_;
    if (block <= last_block_) return;
    last_block_ = block;
    history_.Publish(SnapshotOf(r, t0_ns));
  }

 private:
  LiveSnapshotHistory& history_;
  std::int64_t every_cycles_;
  std::int64_t last_block_ = -1;
};

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

// {"sequence", "cycle", "pairs_touching", "contacts", "not_kept", "points": base64 of float32
// x,y,z (world, m), "normals": base64 of float32 unit x,y,z, "pair": base64 of int32 pair
// indices}.
std::string PairContactsJson(const PairContactFrame& frame);

// A series a live view streams beside the snapshots, as "event: EVENT" events, its newest at
// "/EVENT": the contact marks of a pointshell (PointMarksFeed) or the contacts of every pair of a
// scene of many bodies (PairContactsFeed), published lock-free by the haptic thread.
struct LiveMarksFrame {
  std::uint64_t sequence = 0;  // 0: none yet
  std::int64_t last_cycle = 0;
  std::string json;
};
class LiveMarks {
 public:
  virtual ~LiveMarks() = default;
  virtual const char* event() const = 0;
  // Reader (one thread at a time): the newest frame, as JSON, into *FRAME when newer than its
  // sequence; false when there is none newer.
  virtual bool TakeLatest(LiveMarksFrame* frame) = 0;
};

// ContactPointMarks as "marks" events (MarksJson). MARKS must outlive the feed.
class PointMarksFeed final : public LiveMarks {
 public:
  explicit PointMarksFeed(ContactPointMarks& marks) : marks_(marks) {}
  const char* event() const override { return "marks"; }
  bool TakeLatest(LiveMarksFrame* frame) override;

 private:
  ContactPointMarks& marks_;
  PointMarkSweep sweep_;
};

// PairContactMarks as "pair-contacts" events (PairContactsJson). MARKS must outlive the feed.
class PairContactsFeed final : public LiveMarks {
 public:
  explicit PairContactsFeed(PairContactMarks& marks) : marks_(marks) {}
  const char* event() const override { return "pair-contacts"; }
  bool TakeLatest(LiveMarksFrame* frame) override;

 private:
  PairContactMarks& marks_;
  PairContactFrame frame_;
};

// Event streams a live view serves at once; one more is answered 503. The server answers
// complete requests with a thread per open stream and kLiveViewSpareThreads more, so the page,
// /snapshot and /marks are always answered however many streams are open. A connection holds
// none of them while its request head arrives (view/request_gate.h): every head must arrive in
// full within kLiveViewHeadSeconds of the connection (or of the previous response), however it
// trickles, else the connection is closed; idle connections wait at one gate thread, at most
// kLiveViewWaitingLimit of them (the oldest closed past it).
inline constexpr int kLiveViewStreamLimit = 16;
inline constexpr int kLiveViewSpareThreads = 4;
inline constexpr int kLiveViewHeadSeconds = 2;
inline constexpr int kLiveViewWaitingLimit = 256;

class GatedHttpServer;

class LiveViewServer {
 public:
  // Serves PAGE.html at "/" and each of PAGE.files at "/" + its path, the snapshots of SOURCE at
  // "/stream" (text/event-stream, one "data: JSON" event per snapshot, each snapshot once and in
  // order, starting from the newest when the stream opens or from the first when none was published
  // yet) and the newest one at "/snapshot" (JSON; 204 before the first), on 127.0.0.1:PORT (0: a
  // free port). At most kLiveViewStreamLimit streams at once (503 past it); methods other than GET
  // and HEAD get 405 without their body being read; a request head must arrive within
  // kLiveViewHeadSeconds, each read and write of an answer within 2 s, and a whole answer other
  // than a stream within 10 s, else the connection is cut. With MARKS, the stream also sends
  // "event: " + MARKS.event() + "data: " its frame's JSON when a newer frame completed at least
  // MARKS_EVERY_CYCLES haptic cycles after the last one it sent, and "/" + MARKS.event() returns
  // the newest (204 before the first). SOURCE and MARKS must outlive the server. Throws Error
  // naming the address when it cannot bind.
  LiveViewServer(ServedPage page, const LiveSnapshotHistory& source, int port, LiveMarks* marks = nullptr,
                 std::int64_t marks_every_cycles = 67);
  ~LiveViewServer();
  LiveViewServer(const LiveViewServer&) = delete;
  LiveViewServer& operator=(const LiveViewServer&) = delete;

  int port() const { return port_; }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/"; }
  // Streams opened so far (GET /stream answered with a stream; HEAD opens none).
  int streams_opened() {
    std::lock_guard<std::mutex> lock(streams_mutex_);
    return streams_opened_;
  }

  // Blocks until COUNT streams were opened (since the server started), or GIVE_UP returns
  // true (asked a few times a second, e.g. a stop signal); returns whether they were. A
  // stream opened before any snapshot was published sends them all from the first.
  bool WaitForStreams(int count, const std::function<bool()>& give_up);

  // Ends the streams and stops serving (also done by the destructor). Each open stream first
  // sends every snapshot published before the call (and the newest marks when due), then
  // ends cleanly; a stream whose client does not read is cut after a few seconds.
  void Stop();

 private:
  // The newest frame of marks, shared by the stream threads (TakeLatest has one reader at a
  // time).
  LiveMarksFrame LatestMarks();
  struct StreamState;

  // The constructor's steps (live_view_server.cc says what each does).
  void LimitConnections();
  void RoutePage();
  void RouteLatest();
  void RouteStream();
  void BindAndServe(int port);
  // A stream's life: counted in (false past the limit), its events, counted out.
  bool OpenStream();
  bool SendStreamEvents(StreamState& stream, httplib::DataSink& sink);
  void CloseStream();

  ServedPage page_;
  const LiveSnapshotHistory& source_;
  LiveMarks* marks_;
  std::int64_t marks_every_cycles_;
  std::mutex marks_mutex_;
  LiveMarksFrame marks_frame_;
  int port_ = 0;
  std::unique_ptr<GatedHttpServer> server_;
  std::thread thread_;
  // The streams: opened so far, still open, and whether the server is stopping (streams_mutex_).
  std::mutex streams_mutex_;
  std::condition_variable streams_changed_;
  int streams_opened_ = 0;
  int streams_open_ = 0;
  bool stopping_ = false;
};

}  // namespace contactlab
