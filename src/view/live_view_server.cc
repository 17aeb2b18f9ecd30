#include "view/live_view_server.h"

// After the headers that include Eigen: httplib.h brings <resolv.h>, whose macro _res breaks
// Eigen's headers.
#include "view/request_gate.h"

#include <chrono>
#include <cstdio>

#include "util/error.h"
#include "view/page_encoding.h"

namespace contactlab {

LiveSnapshot SnapshotOf(const CycleRecord& r, std::int64_t t0_ns) {
  LiveSnapshot s;
  s.t = double(r.now_ns - t0_ns) * 1e-9;
  s.cycle = r.cycle;
  for (int k = 0; k < 3; ++k) {
    s.p_WH[k] = r.p_WH[k];
    s.p_WD[k] = r.p_WD[k];
    s.contact_force[k] = r.contact_force[k];
    s.device_force[k] = r.device_force[k];
    s.device_torque[k] = r.device_torque[k];
  }
  for (int k = 0; k < 4; ++k) {
    s.q_WH[k] = r.q_WH[k];
    s.q_WD[k] = r.q_WD[k];
  }
  s.has_proxy = r.has_proxy;
  for (int k = 0; k < 3; ++k) s.p_WP[k] = r.p_WP[k];
  for (int k = 0; k < 4; ++k) s.q_WP[k] = r.q_WP[k];
  s.points_in_contact = r.points_in_contact;
  s.level_rendered = r.level_rendered;
  s.work_us = double(r.work_ns) * 1e-3;
  s.safety_flags = r.safety_flags;
  return s;
}

std::string SnapshotJson(const LiveSnapshot& s) {
  char proxy[256] = "null";
  if (s.has_proxy) {
    std::snprintf(proxy, sizeof proxy, "[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g]", s.p_WP[0], s.p_WP[1], s.p_WP[2], s.q_WP[0],
                  s.q_WP[1], s.q_WP[2], s.q_WP[3]);
  }
  char buf[1280];
  std::snprintf(buf, sizeof buf,
                "{\"t\":%.6f,\"cycle\":%lld,\"body\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],"
                "\"device\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],\"contact_force\":[%.9g,%.9g,%.9g],"
                "\"force\":[%.9g,%.9g,%.9g],\"torque\":[%.9g,%.9g,%.9g],\"contacts\":%d,\"level\":%d,"
                "\"work_us\":%.3f,\"safety\":%u,\"proxy\":%s}",
                s.t, static_cast<long long>(s.cycle), s.p_WH[0], s.p_WH[1], s.p_WH[2], s.q_WH[0], s.q_WH[1], s.q_WH[2],
                s.q_WH[3], s.p_WD[0], s.p_WD[1], s.p_WD[2], s.q_WD[0], s.q_WD[1], s.q_WD[2], s.q_WD[3],
                s.contact_force[0], s.contact_force[1], s.contact_force[2], s.device_force[0], s.device_force[1],
                s.device_force[2], s.device_torque[0], s.device_torque[1], s.device_torque[2], s.points_in_contact,
                s.level_rendered, s.work_us, s.safety_flags, proxy);
  return buf;
}

std::string PackPointStates(const std::vector<PointState>& states) {
  std::string bytes((states.size() + 3) / 4, '\0');
  for (std::size_t k = 0; k < states.size(); ++k) {
    bytes[k / 4] = char(std::uint8_t(bytes[k / 4]) | (std::uint8_t(states[k]) << (2 * (k % 4))));
  }
  return bytes;
}

std::string MarksJson(const PointMarkSweep& s) {
  char head[256];
  std::snprintf(head, sizeof head,
                "{\"sequence\":%llu,\"first_cycle\":%lld,\"last_cycle\":%lld,\"points\":%zu,\"in_contact\":%d,"
                "\"evaluated\":%d,\"states\":\"",
                static_cast<unsigned long long>(s.sequence), static_cast<long long>(s.first_cycle),
                static_cast<long long>(s.last_cycle), s.states.size(), s.in_contact, s.evaluated);
  return head + Base64Encode(PackPointStates(s.states)) + "\"}";
}

std::string PairContactsJson(const PairContactFrame& f) {
  char head[256];
  std::snprintf(head, sizeof head,
                "{\"sequence\":%llu,\"cycle\":%lld,\"pairs_touching\":%d,\"contacts\":%d,\"not_kept\":%lld,"
                "\"points\":\"",
                static_cast<unsigned long long>(f.sequence), static_cast<long long>(f.cycle), f.pairs_touching,
                f.size(), static_cast<long long>(f.not_kept));
  return head + EncodeArray(f.points) + "\",\"normals\":\"" +
         EncodeArray(f.normals) + "\",\"pair\":\"" +
         EncodeArray(f.pair) + "\"}";
}

bool PointMarksFeed::TakeLatest(LiveMarksFrame* frame) {
  if (!marks_.TakeLatest(&sweep_)) return false;
  *frame = {sweep_.sequence, sweep_.last_cycle, MarksJson(sweep_)};
  return true;
}

bool PairContactsFeed::TakeLatest(LiveMarksFrame* frame) {
  if (!marks_.TakeLatest(&frame_)) return false;
  *frame = {frame_.sequence, frame_.cycle, PairContactsJson(frame_)};
  return true;
}

namespace {

// How often an idle stream looks for new snapshots and marks. Latency only: which snapshots a
// stream sends does not depend on it.
constexpr std::chrono::milliseconds kStreamPoll{10};
// How long Stop() lets the open streams send what is left before it cuts them (a client that
// does not read).
constexpr std::chrono::seconds kStreamDrain{5};

// A regular expression (httplib's routes are ECMAScript ones) that matches TEXT alone.
std::string RegexMatching(const std::string& text) {
  std::string pattern;
  for (char c : text) {
    if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) pattern += '\\';
    pattern += c;
  }
  return pattern;
}

}  // namespace

LiveSnapshotPublisher::LiveSnapshotPublisher(LiveSnapshotHistory& history, std::int64_t every_cycles)
    : history_(history), every_cycles_(every_cycles) {
  if (every_cycles_ <= 0) Fail("live view", "snapshots must be taken every N > 0 cycles");
}

LiveMarksFrame LiveViewServer::LatestMarks() {
  std::lock_guard<std::mutex> lock(marks_mutex_);
  (void)marks_->TakeLatest(&marks_frame_);
  return marks_frame_;
}

LiveViewServer::LiveViewServer(ServedPage page, const LiveSnapshotHistory& source, int port, LiveMarks* marks,
                               std::int64_t marks_every_cycles)
    : page_(std::move(page)),
      source_(source),
      marks_(marks),
      marks_every_cycles_(marks_every_cycles),
      server_(std::make_unique<GatedHttpServer>(
          RequestGateLimits{.workers = kLiveViewStreamLimit + kLiveViewSpareThreads,
                            .max_waiting = kLiveViewWaitingLimit,
                            .head_timeout = std::chrono::seconds(kLiveViewHeadSeconds)},
          [](std::string_view target) { return target == "/stream"; })) {
  if (marks_every_cycles_ <= 0) Fail("live view", "marks must be at least 1 cycle apart");
  if (port < 0 || port > 65535) Fail("--view", "port " + std::to_string(port) + " is not in 0..65535");
  LimitConnections();
  RoutePage();
  RouteLatest();
  RouteStream();
  BindAndServe(port);
}

// A thread per stream the limit allows and spares for everything else (the gate's workers): a
// stream holds its thread for its whole life, a connection none until its request arrived in
// full (request_gate.h). Only GET and HEAD: anything else is refused before its body is read (a
// POST without a body would otherwise wait for one until the read timeout).
void LiveViewServer::LimitConnections() {
  server_->set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    if (req.method == "GET" || req.method == "HEAD") return httplib::Server::HandlerResponse::Unhandled;
    res.status = 405;
    res.set_header("Allow", "GET, HEAD");
    res.set_header("Connection", "close");
    res.set_content("the live view answers GET and HEAD only\n", "text/plain");
    return httplib::Server::HandlerResponse::Handled;
  });
}

// The page at "/" and each of its files at "/" + its path; the files are asked to be checked
// again before reuse, so a browser never runs a cached script of another version beside the page.
void LiveViewServer::RoutePage() {
  server_->Get("/", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(page_.html, "text/html; charset=utf-8");
  });
  for (const ServedFile& file : page_.files) {
    server_->Get(RegexMatching("/" + file.path), [&file](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      res.set_content(file.content, file.content_type);
    });
  }
}

// The newest snapshot and marks at "/snapshot" and "/" + the marks' event (204 before the first).
void LiveViewServer::RouteLatest() {
  server_->Get("/snapshot", [this](const httplib::Request&, httplib::Response& res) {
    LiveSnapshot s;
    if (!source_.Latest(&s)) {
      res.status = 204;
      return;
    }
    res.set_content(SnapshotJson(s), "application/json");
  });
  server_->Get(std::string("/") + (marks_ ? marks_->event() : "marks"), [this](const httplib::Request&, httplib::Response& res) {
    const LiveMarksFrame m = marks_ ? LatestMarks() : LiveMarksFrame{};
    if (m.sequence == 0) {
      res.status = 204;
      return;
    }
    res.set_content(m.json, "application/json");
  });
}

// Where one event stream is: the next snapshot to send, and the last marks sent (0: none yet)
// and their cycle.
struct LiveViewServer::StreamState {
  std::uint64_t next = 0;
  std::uint64_t marks_sequence = 0;
  std::int64_t marks_cycle = 0;
};

// Server-sent events at "/stream": every snapshot of the history once and in order from where
// the stream joined, and the newest marks when due; the stream ends when the server stops
// (after sending what was published before) or the client goes away.
void LiveViewServer::RouteStream() {
  server_->Get("/stream", [this](const httplib::Request& req, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    if (req.method == "HEAD") {  // what a GET would get, with no stream opened or counted
      res.set_header("Content-Type", "text/event-stream");
      return;
    }
    if (!OpenStream()) {
      res.status = 503;
      res.set_content("the live view serves at most " + std::to_string(kLiveViewStreamLimit) +
                          " streams at once; close one and retry\n",
                      "text/plain");
      return;
    }
    auto stream = std::make_shared<StreamState>();
    const std::uint64_t published = source_.published();
    stream->next = published > 0 ? published - 1 : 0;
    streams_changed_.notify_all();
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, stream](std::size_t, httplib::DataSink& sink) { return SendStreamEvents(*stream, sink); },
        [this](bool) { CloseStream(); });
  });
}

// Counts a stream in, unless kLiveViewStreamLimit are open (then false).
bool LiveViewServer::OpenStream() {
  std::lock_guard<std::mutex> lock(streams_mutex_);
  if (streams_open_ >= kLiveViewStreamLimit) return false;
  ++streams_opened_;
  ++streams_open_;
  return true;
}

// Counts a stream out, when httplib is done with it.
void LiveViewServer::CloseStream() {
  {
    std::lock_guard<std::mutex> lock(streams_mutex_);
    --streams_open_;
  }
  streams_changed_.notify_all();
}

// The chunked content provider of one stream (its thread): writes what was published since
// the last call, or waits for it; returns false when the client went away.
bool LiveViewServer::SendStreamEvents(StreamState& stream, httplib::DataSink& sink) {
  for (;;) {
    // Whether the server stops, before looking: what was published before Stop() is then all
    // there.
    bool stopping;
    {
      std::lock_guard<std::mutex> lock(streams_mutex_);
      stopping = stopping_;
    }
    bool wrote = false;
    // The newest marks, when a sweep completed at least marks_every_cycles_ after the last one
    // sent. Looked for after each snapshot that is that far on (and while none was sent, and at
    // the end), so that marks go out in session time, between the snapshots, and a sweep is
    // copied and encoded only when it may be due.
    const auto send_marks_when_due = [&](bool look) {
      if (!marks_ || !look) return true;
      const LiveMarksFrame m = LatestMarks();
      if (m.sequence == 0 || m.sequence == stream.marks_sequence) return true;
      if (stream.marks_sequence != 0 && m.last_cycle - stream.marks_cycle < marks_every_cycles_) return true;
      stream.marks_sequence = m.sequence;
      stream.marks_cycle = m.last_cycle;
      const std::string event = std::string("event: ") + marks_->event() + "\ndata: " + m.json + "\n\n";
      wrote = true;
      return sink.write(event.data(), event.size());
    };
    // Every snapshot published since the last look, in order; a stream more than the history
    // behind skips to the newest.
    for (LiveSnapshot s;;) {
      const HistoryRead read = source_.Get(stream.next, &s);
      if (read == HistoryRead::kNotYet) break;
      if (read == HistoryRead::kOverwritten) {
        stream.next = source_.published() - 1;
        continue;
      }
      ++stream.next;
      const std::string event = "data: " + SnapshotJson(s) + "\n\n";
      if (!sink.write(event.data(), event.size())) return false;
      wrote = true;
      if (!send_marks_when_due(stream.marks_sequence == 0 || s.cycle - stream.marks_cycle >= marks_every_cycles_))
        return false;
    }
    if (!send_marks_when_due(stream.marks_sequence == 0 || stopping)) return false;
    if (stopping) {
      sink.done();
      return true;
    }
    if (wrote) return true;
    {
      std::unique_lock<std::mutex> lock(streams_mutex_);
      streams_changed_.wait_for(lock, kStreamPoll, [&] { return stopping_; });
    }
    if (!sink.is_writable()) return false;
  }
}

// Binds 127.0.0.1:PORT (0: a free port) and serves on thread_. Loopback only: the page and the
// stream never leave this machine. Returns once serving, so that Stop() always finds a running
// server to stop.
void LiveViewServer::BindAndServe(int port) {
  if (port == 0) {
    port_ = server_->bind_to_any_port("127.0.0.1");
    if (port_ <= 0) Fail("127.0.0.1", "cannot bind a free port for the live view");
  } else {
    if (!server_->bind_to_port("127.0.0.1", port)) {
      Fail("127.0.0.1:" + std::to_string(port), "cannot bind the live view's port (in use?)");
    }
    port_ = port;
  }
  server_->WidenBacklog();
  thread_ = std::thread([this] { server_->listen_after_bind(); });
  for (int i = 0; i < 2000 && !server_->is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

LiveViewServer::~LiveViewServer() { Stop(); }

bool LiveViewServer::WaitForStreams(int count, const std::function<bool()>& give_up) {
  std::unique_lock<std::mutex> lock(streams_mutex_);
  while (streams_opened_ < count) {
    if (give_up && give_up()) return false;
    streams_changed_.wait_for(lock, std::chrono::milliseconds(100), [&] { return streams_opened_ >= count; });
  }
  return true;
}

void LiveViewServer::Stop() {
  {
    std::unique_lock<std::mutex> lock(streams_mutex_);
    stopping_ = true;
    streams_changed_.notify_all();
    streams_changed_.wait_for(lock, kStreamDrain, [&] { return streams_open_ == 0; });
  }
  if (server_) server_->stop();
  if (thread_.joinable()) thread_.join();
  if (server_) server_->StopGate();
}

}  // namespace contactlab
