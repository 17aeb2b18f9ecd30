#include "view/live_view_server.h"

// After the headers that include Eigen: httplib.h brings <resolv.h>, whose macro _res breaks
// Eigen's headers.
#include <httplib.h>

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
  s.points_in_contact = r.points_in_contact;
  s.level_rendered = r.level_rendered;
  s.work_us = double(r.work_ns) * 1e-3;
  s.safety_flags = r.safety_flags;
  return s;
}

std::string SnapshotJson(const LiveSnapshot& s) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "{\"t\":%.6f,\"cycle\":%lld,\"body\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],"
                "\"device\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],\"contact_force\":[%.9g,%.9g,%.9g],"
                "\"force\":[%.9g,%.9g,%.9g],\"torque\":[%.9g,%.9g,%.9g],\"contacts\":%d,\"level\":%d,"
                "\"work_us\":%.3f,\"safety\":%u}",
                s.t, static_cast<long long>(s.cycle), s.p_WH[0], s.p_WH[1], s.p_WH[2], s.q_WH[0], s.q_WH[1], s.q_WH[2],
                s.q_WH[3], s.p_WD[0], s.p_WD[1], s.p_WD[2], s.q_WD[0], s.q_WD[1], s.q_WD[2], s.q_WD[3],
                s.contact_force[0], s.contact_force[1], s.contact_force[2], s.device_force[0], s.device_force[1],
                s.device_force[2], s.device_torque[0], s.device_torque[1], s.device_torque[2], s.points_in_contact,
                s.level_rendered, s.work_us, s.safety_flags);
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

std::pair<std::uint64_t, std::string> LiveViewServer::LatestMarks() {
  std::lock_guard<std::mutex> lock(marks_mutex_);
  if (marks_->TakeLatest(&marks_sweep_)) marks_json_ = MarksJson(marks_sweep_);
  return {marks_sweep_.sequence, marks_json_};
}

LiveViewServer::LiveViewServer(std::string page, const LatestValue<LiveSnapshot>& source, int port, double rate_hz,
                               ContactPointMarks* marks, double marks_rate_hz)
    : page_(std::move(page)),
      source_(source),
      rate_hz_(rate_hz),
      marks_(marks),
      marks_rate_hz_(marks_rate_hz),
      server_(std::make_unique<httplib::Server>()) {
  if (!(rate_hz_ > 0 && rate_hz_ <= 1000)) Fail("live view", "stream rate must be in (0, 1000] Hz");
  if (!(marks_rate_hz_ > 0 && marks_rate_hz_ <= rate_hz_)) Fail("live view", "marks rate must be in (0, stream rate] Hz");
  if (port < 0 || port > 65535) Fail("--view", "port " + std::to_string(port) + " is not in 0..65535");

  server_->Get("/", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(page_, "text/html; charset=utf-8");
  });
  server_->Get("/snapshot", [this](const httplib::Request&, httplib::Response& res) {
    LiveSnapshot s;
    if (!source_.Load(&s)) {
      res.status = 204;
      return;
    }
    res.set_content(SnapshotJson(s), "application/json");
  });
  server_->Get("/marks", [this](const httplib::Request&, httplib::Response& res) {
    const auto [sequence, json] = marks_ ? LatestMarks() : std::pair<std::uint64_t, std::string>{0, ""};
    if (sequence == 0) {
      res.status = 204;
      return;
    }
    res.set_content(json, "application/json");
  });
  // Server-sent events: each new snapshot once, polled at the stream's rate, and the newest
  // marks at their lower rate; the stream ends when the server stops or the client goes away.
  server_->Get("/stream", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-cache");
    auto last = std::make_shared<std::uint64_t>(0);
    auto last_marks = std::make_shared<std::uint64_t>(0);
    auto marks_due = std::make_shared<std::chrono::steady_clock::time_point>();
    res.set_chunked_content_provider("text/event-stream", [this, last, last_marks, marks_due](std::size_t,
                                                                                             httplib::DataSink& sink) {
      const auto period = std::chrono::duration<double>(1.0 / rate_hz_);
      for (;;) {
        if (stopping_.load()) {
          sink.done();
          return true;
        }
        if (marks_ && std::chrono::steady_clock::now() >= *marks_due) {
          const auto [sequence, json] = LatestMarks();
          if (sequence != 0 && sequence != *last_marks) {
            *last_marks = sequence;
            *marks_due = std::chrono::steady_clock::now() +
                         std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                             std::chrono::duration<double>(1.0 / marks_rate_hz_));
            const std::string event = "event: marks\ndata: " + json + "\n\n";
            if (!sink.write(event.data(), event.size())) return false;
          }
        }
        LiveSnapshot s;
        const std::uint64_t version = source_.version();
        if (version != *last && source_.Load(&s)) {
          *last = version;
          const std::string event = "data: " + SnapshotJson(s) + "\n\n";
          if (!sink.write(event.data(), event.size())) return false;
          std::this_thread::sleep_for(period);
          return true;
        }
        std::this_thread::sleep_for(period);
        if (!sink.is_writable()) return false;
      }
    });
  });

  // Loopback only: the page and the stream never leave this machine.
  if (port == 0) {
    port_ = server_->bind_to_any_port("127.0.0.1");
    if (port_ <= 0) Fail("127.0.0.1", "cannot bind a free port for the live view");
  } else {
    if (!server_->bind_to_port("127.0.0.1", port)) {
      Fail("127.0.0.1:" + std::to_string(port), "cannot bind the live view's port (in use?)");
    }
    port_ = port;
  }
  thread_ = std::thread([this] { server_->listen_after_bind(); });
  // Serving before returning, so that Stop() always finds a running server to stop.
  for (int i = 0; i < 2000 && !server_->is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

LiveViewServer::~LiveViewServer() { Stop(); }

void LiveViewServer::Stop() {
  stopping_.store(true);
  if (server_) server_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace contactlab
