// The live view of a session end to end: `contactlab session ... --view` on a free loopback
// port, its page and event stream read with httplib::Client while the session runs, and every
// streamed snapshot checked against the session's log row of the same cycle. Nothing here
// depends on how fast the session, its threads or this test run: snapshots are taken by
// session time (cycles), each stream sends every one of them in order, the session waits for
// its viewer (--view-wait) and, when it ends, sends what is left before ending the stream.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <span>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/studies/contact/result_csv.h"
#include "allocation_counter.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "view/page_encoding.h"
#include "view/latest_value.h"
#include "view/live_view_server.h"
#include "view/request_gate.h"
#include "view/snapshot_history.h"

// After every header that includes Eigen: httplib.h brings <resolv.h>, whose macro _res breaks
// Eigen's headers.
#include <httplib.h>

namespace contactlab {
namespace {

using testing::TempDir;

// A ball (pointshell) and a plate (field, the haptic body) pushed into it by a simulated hand
// moving on a circle: the shared ball on plate (tests/scene_fixtures.h).
const std::string kScene = testing::BallOnPlate{.name = "live-ball-plate"}.Yaml();

TEST(LatestValue, ReadersSeeWholeValuesOnly) {
  struct Pair {
    double a, b;  // always equal
  };
  LatestValue<Pair> v;
  Pair p;
  EXPECT_FALSE(v.Load(&p));
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    double x = 1;
    do {
      v.Store({x, x});
      x += 1;
      std::this_thread::yield();  // on a shared core, let the reader in after every value
    } while (!stop.load());
  });
  // Reads while the writer writes, until 1000 different values were seen. Both threads
  // yield, so that on a loaded machine, where they share a core, a new value costs a switch
  // and not a time slice; the deadline only guards against a hang.
  int torn = 0, changes = 0, backwards = 0;
  double previous = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (changes < 1000 && std::chrono::steady_clock::now() < deadline) {
    if (!v.Load(&p)) continue;
    if (p.a != p.b) ++torn;
    if (p.a < previous) ++backwards;  // an older value after a newer one
    if (p.a != previous) {
      ++changes;
    } else {
      std::this_thread::yield();
    }
    previous = p.a;
  }
  stop.store(true);
  writer.join();
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_EQ(changes, 1000);
  EXPECT_GT(v.version(), 0u);
}

// The hand-off could run on the haptic thread itself: making and storing a snapshot allocates
// nothing (and takes no lock: LatestValue has none).
TEST(LatestValue, StoringSnapshotsAllocatesNothing) {
  LatestValue<LiveSnapshot> v;
  CycleRecord r;
  r.now_ns = 7'000'000;
  r.p_WH[0] = 0.25;
  r.contact_force[2] = 4.5;
  const long before = testing::AllocationCount();
  for (int i = 0; i < 1000; ++i) {
    r.cycle = i;
    v.Store(SnapshotOf(r, 2'000'000));
  }
  LiveSnapshot s;
  const bool loaded = v.Load(&s);
  EXPECT_EQ(testing::AllocationCount(), before);
  ASSERT_TRUE(loaded);
  EXPECT_EQ(s.cycle, 999);
  EXPECT_DOUBLE_EQ(s.t, 0.005);
  EXPECT_DOUBLE_EQ(s.p_WH[0], 0.25);
  EXPECT_DOUBLE_EQ(s.contact_force[2], 4.5);
  EXPECT_EQ(v.version(), 1000u);
}

// A value of the history tests: both fields always equal, so a torn copy shows.
struct Numbered {
  std::uint64_t a, b;
};

TEST(SnapshotHistory, ReaderLearnsWhatIsThereNotYetAndOverwritten) {
  SnapshotHistory<Numbered, 4> h;
  Numbered v{};
  EXPECT_EQ(h.published(), 0u);
  EXPECT_FALSE(h.Latest(&v));
  EXPECT_EQ(h.Get(0, &v), HistoryRead::kNotYet);
  for (std::uint64_t k = 0; k < 6; ++k) h.Publish({k, k});
  EXPECT_EQ(h.published(), 6u);
  EXPECT_EQ(h.Get(0, &v), HistoryRead::kOverwritten);  // by 4
  EXPECT_EQ(h.Get(1, &v), HistoryRead::kOverwritten);  // by 5
  for (std::uint64_t k = 2; k < 6; ++k) {
    ASSERT_EQ(h.Get(k, &v), HistoryRead::kOk) << k;
    EXPECT_EQ(v.a, k);
  }
  EXPECT_EQ(h.Get(6, &v), HistoryRead::kNotYet);
  ASSERT_TRUE(h.Latest(&v));
  EXPECT_EQ(v.a, 5u);
}

// A reader that follows a writer reads each value whole and in order, or learns that it fell
// behind and skips; it ends when the writer has published all, however the two are scheduled.
TEST(SnapshotHistory, FollowingReaderSeesWholeValuesInOrder) {
  static SnapshotHistory<Numbered, 16> h;  // small: the reader sometimes falls behind
  constexpr std::uint64_t kN = 100000;
  std::thread writer([] {
    for (std::uint64_t k = 0; k < kN; ++k) {
      h.Publish({k, k});
      if (k % 8 == 0) std::this_thread::yield();  // on a shared core, let the reader in
    }
  });
  std::uint64_t read = 0, torn = 0, wrong = 0;
  for (std::uint64_t k = 0; k < kN;) {
    Numbered v;
    switch (h.Get(k, &v)) {
      case HistoryRead::kOk:
        torn += v.a != v.b;
        wrong += v.a != k;
        ++read;
        ++k;
        break;
      case HistoryRead::kOverwritten:
        k = h.published() - 1;  // as a stream does: on to the newest
        break;
      case HistoryRead::kNotYet:
        std::this_thread::yield();
        break;
    }
  }
  writer.join();
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(read, 0u);
}

// Snapshots are chosen by the cycles of the records, not by when they arrive: the first record
// of every block of 20 cycles, also when records are missing (dropped by a lagging consumer).
TEST(LiveSnapshotPublisher, TakesTheFirstRecordOfEveryBlockOfCycles) {
  auto history = std::make_unique<LiveSnapshotHistory>();
  LiveSnapshotPublisher publisher(*history, 20);
  CycleRecord r;
  const std::int64_t t0 = 5'000'000'000;
  for (std::int64_t cycle = 0; cycle < 100; ++cycle) {
    if (cycle >= 37 && cycle <= 41) continue;  // records lost: block 2 starts at 42
    r.cycle = cycle;
    r.now_ns = t0 + cycle * 1'000'000;
    publisher.Offer(r, t0);
  }
  ASSERT_EQ(history->published(), 5u);
  const std::int64_t expected[5] = {0, 20, 42, 60, 80};
  for (std::uint64_t k = 0; k < 5; ++k) {
    LiveSnapshot s;
    ASSERT_EQ(history->Get(k, &s), HistoryRead::kOk);
    EXPECT_EQ(s.cycle, expected[k]);
    EXPECT_DOUBLE_EQ(s.t, expected[k] * 1e-3);
  }
  EXPECT_THROW(LiveSnapshotPublisher(*history, 0), Error);
}

// The events of a stream: snapshots (as JSON) and marks, in the order they came.
struct StreamEvents {
  std::string buffer;
  std::vector<nlohmann::json> snapshots, marks;
  std::vector<char> order;  // 's' or 'm' per event
  // Takes N more bytes; returns the number of complete events seen so far.
  std::size_t Add(const char* data, std::size_t n) {
    buffer.append(data, n);
    for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos;) {
      const std::string event = buffer.substr(0, end);
      buffer.erase(0, end + 2);
      const std::string marks_prefix = "event: marks\ndata: ";
      if (event.rfind(marks_prefix, 0) == 0) {
        marks.push_back(nlohmann::json::parse(event.substr(marks_prefix.size())));
        order.push_back('m');
        continue;
      }
      EXPECT_EQ(event.rfind("data: ", 0), 0u) << event;
      snapshots.push_back(nlohmann::json::parse(event.substr(6)));
      order.push_back('s');
    }
    return order.size();
  }
};

TEST(LiveView, ServerStreamsTheNewestSnapshotOnLoopback) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html>page</html>", {{"viewer/a.js", "export const A = 1;\n", "text/javascript"}}},
                        *source, 0);
  ASSERT_GT(server.port(), 0);
  httplib::Client client("127.0.0.1", server.port());
  // Before the first snapshot: the page, and no snapshot.
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->body, "<html>page</html>");
  // The page's file at its path, and nothing at a path that differs in a character the route's
  // pattern would otherwise match (the dot).
  auto file = client.Get("/viewer/a.js");
  ASSERT_TRUE(file);
  EXPECT_EQ(file->status, 200);
  EXPECT_EQ(file->body, "export const A = 1;\n");
  EXPECT_EQ(file->get_header_value("Content-Type"), "text/javascript");
  auto other = client.Get("/viewer/aXjs");
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 404);
  auto none = client.Get("/snapshot");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 204);
  LiveSnapshot s;
  s.t = 1.48;
  s.cycle = 1480;
  source->Publish(s);
  s.t = 1.5;
  s.cycle = 1500;
  s.p_WH[2] = -0.25;
  s.contact_force[2] = 3.0;
  s.level_rendered = 2;
  source->Publish(s);
  auto one = client.Get("/snapshot");
  ASSERT_TRUE(one);
  const nlohmann::json j = nlohmann::json::parse(one->body);
  EXPECT_EQ(j["cycle"], 1500);
  EXPECT_DOUBLE_EQ(j["body"][2].get<double>(), -0.25);
  EXPECT_DOUBLE_EQ(j["contact_force"][2].get<double>(), 3.0);
  EXPECT_EQ(j["level"], 2);
  EXPECT_TRUE(j["proxy"].is_null());  // no proxy in this session's model
  // A model with a proxy (pointshell-ccd): its pose travels with the snapshot.
  s.has_proxy = true;
  s.p_WP[0] = 0.125;
  s.q_WP[0] = 0.5, s.q_WP[3] = -0.5;
  const nlohmann::json with = nlohmann::json::parse(SnapshotJson(s));
  ASSERT_EQ(with["proxy"].size(), 7u);
  EXPECT_DOUBLE_EQ(with["proxy"][0].get<double>(), 0.125);
  EXPECT_DOUBLE_EQ(with["proxy"][3].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(with["proxy"][6].get<double>(), -0.5);
  // A stream opened now starts with the newest as an event.
  std::string got;
  client.Get("/stream", [&](const char* data, std::size_t n) {
    got.append(data, n);
    return got.find("\n\n") == std::string::npos;
  });
  EXPECT_EQ(got.rfind("data: {\"t\":1.500000,\"cycle\":1500,", 0), 0u) << got;
  server.Stop();
  EXPECT_FALSE(client.Get("/"));
}

// A stream sends every snapshot published after it joined, once and in order, however they
// are spread in time: here the client publishes the next ones (five at once, then one, then
// five) as it receives the first, second and third, so the stream's thread meets them in
// whatever rhythm it runs. The client stops at the last one published, which a stream that
// skips reaches early.
TEST(LiveView, StreamSendsEverySnapshotOnceInOrderFromWhereItJoined) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html></html>"}, *source, 0);
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(60, 0);  // a hang guard only
  std::int64_t cycle = 0;
  const auto publish = [&](int n) {
    for (int i = 0; i < n; ++i) {
      LiveSnapshot s;
      s.cycle = cycle;
      s.t = double(cycle) * 1e-3;
      source->Publish(s);
      cycle += 20;
    }
  };
  publish(3);  // cycles 0, 20, 40: the stream joins at the newest (40)
  const int rounds[3] = {5, 1, 5};  // published on receiving the 1st, 2nd and 3rd snapshot
  StreamEvents events;
  client.Get("/stream", [&](const char* data, std::size_t n) {
    const std::size_t before = events.snapshots.size();
    events.Add(data, n);
    for (std::size_t k = before; k < events.snapshots.size() && k < 3; ++k) publish(rounds[k]);
    return events.snapshots.size() < 3 || events.snapshots.back()["cycle"].get<std::int64_t>() < cycle - 20;
  });
  std::vector<std::int64_t> cycles;
  for (const nlohmann::json& e : events.snapshots) cycles.push_back(e["cycle"].get<std::int64_t>());
  std::vector<std::int64_t> expected;
  for (std::int64_t c = 40; c <= 260; c += 20) expected.push_back(c);
  EXPECT_EQ(cycles, expected);
  EXPECT_TRUE(events.marks.empty());
  server.Stop();
}

// Stop() lets each open stream send every snapshot published before it, then ends the stream
// cleanly; WaitForStreams is how a session (and this test) knows that its viewer is there.
TEST(LiveView, StopEndsEachStreamAfterEverySnapshotPublishedBeforeIt) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html></html>"}, *source, 0);
  StreamEvents events;
  bool ended_cleanly = false;
  std::thread viewer([&] {
    httplib::Client client("127.0.0.1", server.port());
    client.set_read_timeout(60, 0);  // a hang guard only
    const auto res = client.Get("/stream", [&](const char* data, std::size_t n) {
      events.Add(data, n);
      return true;
    });
    ended_cleanly = res && res->status == 200;
  });
  const auto guard = std::chrono::steady_clock::now() + std::chrono::seconds(60);  // a hang guard only
  ASSERT_TRUE(server.WaitForStreams(1, [&] { return std::chrono::steady_clock::now() > guard; }));
  constexpr int kSnapshots = 200;  // fewer than the history holds: none can be overwritten unread
  for (int k = 0; k < kSnapshots; ++k) {
    LiveSnapshot s;
    s.cycle = 20 * k;
    source->Publish(s);
  }
  server.Stop();
  viewer.join();
  EXPECT_TRUE(ended_cleanly);
  ASSERT_EQ(events.snapshots.size(), std::size_t(kSnapshots));
  for (int k = 0; k < kSnapshots; ++k) EXPECT_EQ(events.snapshots[k]["cycle"], 20 * k) << k;
}

// What a raw loopback connection to PORT gets back after sending REQUEST (maybe nothing): all it
// reads until the server closes, or until a 20 s receive timeout (a hang guard only).
std::string RawExchange(int port, const std::string& request) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  EXPECT_GE(fd, 0);
  timeval guard{20, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &guard, sizeof guard);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(std::uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  if (!request.empty()) EXPECT_EQ(send(fd, request.data(), request.size(), 0), ssize_t(request.size()));
  std::string reply;
  char buffer[4096];
  for (ssize_t n; (n = recv(fd, buffer, sizeof buffer, 0)) > 0;) reply.append(buffer, std::size_t(n));
  close(fd);
  return reply;
}

// More watchers than the stream limit cannot starve the live view: with every stream slot held,
// one more stream gets 503, the page and /snapshot are still answered, a POST without a body
// gets 405 at once, a connection that sends nothing is closed, and when the server stops every
// held stream ends cleanly.
TEST(LiveView, StreamsPastTheLimitCannotStarveThePage) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html>live</html>"}, *source, 0);
  std::vector<std::thread> watchers;
  std::vector<int> status(kLiveViewStreamLimit, 0);
  for (int i = 0; i < kLiveViewStreamLimit; ++i) {
    watchers.emplace_back([&, i] {
      httplib::Client client("127.0.0.1", server.port());
      client.set_read_timeout(60, 0);  // a hang guard only
      const auto res = client.Get("/stream", [](const char*, std::size_t) { return true; });
      status[i] = res ? res->status : -1;
    });
  }
  const auto guard = std::chrono::steady_clock::now() + std::chrono::seconds(60);  // a hang guard only
  ASSERT_TRUE(server.WaitForStreams(kLiveViewStreamLimit, [&] { return std::chrono::steady_clock::now() > guard; }));

  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(20, 0);  // a hang guard only
  const auto extra = client.Get("/stream");
  ASSERT_TRUE(extra);
  EXPECT_EQ(extra->status, 503);
  EXPECT_NE(extra->body.find("at most " + std::to_string(kLiveViewStreamLimit) + " streams"), std::string::npos);
  for (int round = 0; round < 3; ++round) {
    const auto page = client.Get("/");
    ASSERT_TRUE(page) << round;
    EXPECT_EQ(page->status, 200);
    EXPECT_EQ(page->body, "<html>live</html>");
    const auto snapshot = client.Get("/snapshot");
    ASSERT_TRUE(snapshot) << round;
    EXPECT_EQ(snapshot->status, 204);  // nothing published yet
  }
  const std::string post = RawExchange(server.port(), "POST / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  EXPECT_EQ(post.rfind("HTTP/1.1 405", 0), 0u) << post;
  EXPECT_EQ(RawExchange(server.port(), ""), "");  // closed by the server's read timeout

  server.Stop();
  for (std::thread& t : watchers) t.join();
  for (int i = 0; i < kLiveViewStreamLimit; ++i) EXPECT_EQ(status[i], 200) << "stream " << i;
}

// HEAD /stream counted as a viewer (a `--view-wait` session started for it), and the gate took
// "/%73tream", which httplib routes to the stream, for a short-lived request and cut it after
// 10 s. HEAD is answered with the stream's headers and opens none; the gate decodes the target
// as the router does.
TEST(LiveView, HeadOpensNoStreamAndTheGateDecodesTheTargetAsTheRouterDoes) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html>live</html>"}, *source, 0);
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(20, 0);  // a hang guard only
  const auto head = client.Head("/stream");
  ASSERT_TRUE(head);
  EXPECT_EQ(head->status, 200);
  EXPECT_EQ(head->get_header_value("Content-Type"), "text/event-stream");
  EXPECT_EQ(server.streams_opened(), 0);
  server.Stop();

  EXPECT_EQ(RequestPath("GET /stream HTTP/1.1\r\n"), "/stream");
  EXPECT_EQ(RequestPath("GET /%73tream HTTP/1.1\r\n"), "/stream");
  EXPECT_EQ(RequestPath("GET /%73%74%72%65%61%6D?x=1 HTTP/1.1\r\n"), "/stream");
  EXPECT_EQ(RequestPath("GET /a%2 HTTP/1.1\r\n"), "/a%2");    // not an escape: kept
  EXPECT_EQ(RequestPath("GET /%zz HTTP/1.1\r\n"), "/%zz");
  EXPECT_EQ(RequestPath("GARBAGE"), "");
}

// Six requests each with a 2,000-part Range header made httplib build every multipart answer in
// memory (1.05 GB each) and the session died of bad_alloc; and no Host was checked, so a web
// page could reach the view through DNS rebinding. The gate now answers a Range of more than
// one part 416 and a foreign Host 421 itself; the loopback names, with the port or without,
// and a request without Host are answered, and the page still is afterwards.
TEST(LiveView, AManyPartRangeOrAForeignHostIsRefusedBeforeHttplibSeesIt) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html>live</html>"}, *source, 0);
  const std::string port = std::to_string(server.port());
  std::string ranges = "bytes=0-";
  for (int k = 1; k < 2000; ++k) ranges += ",0-";
  const std::string many = RawExchange(server.port(), "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + port + "\r\nRange: " +
                                                          ranges + "\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(many.rfind("HTTP/1.1 416", 0), 0u) << many.substr(0, 200);
  EXPECT_LT(many.size(), 1000u);
  const std::string one = RawExchange(server.port(), "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + port +
                                                         "\r\nRange: bytes=0-3\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(one.rfind("HTTP/1.1 206", 0), 0u) << one.substr(0, 200);
  for (const std::string& host : std::vector<std::string>{"evil.example:" + port, "127.0.0.1:1", "127.0.0.1.evil.example", "localhost.:" + port}) {
    const std::string foreign =
        RawExchange(server.port(), "GET / HTTP/1.1\r\nHost: " + host + "\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(foreign.rfind("HTTP/1.1 421", 0), 0u) << host << ": " << foreign.substr(0, 200);
  }
  for (const std::string& host : std::vector<std::string>{"127.0.0.1:" + port, "localhost:" + port, "127.0.0.1", "[::1]:" + port}) {
    const std::string ours =
        RawExchange(server.port(), "GET / HTTP/1.1\r\nhost: " + host + "\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(ours.rfind("HTTP/1.1 200", 0), 0u) << host << ": " << ours.substr(0, 200);
  }
  const std::string no_host = RawExchange(server.port(), "GET / HTTP/1.0\r\n\r\n");
  EXPECT_EQ(no_host.rfind("HTTP/1.1 200", 0), 0u) << no_host.substr(0, 200);
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(20, 0);  // a hang guard only
  const auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->body, "<html>live</html>");
  server.Stop();

  EXPECT_EQ(RequestHeader("GET / HTTP/1.1\r\nX-A: 1\r\nhOsT:  a:1 \r\n\r\nHost: b\r\n", "Host"), "a:1");
  EXPECT_EQ(RequestHeader("GET / HTTP/1.1\r\n\r\n", "Host"), "");
}

// Waits up to TIMEOUT_MS for EVENTS on FD; true when they came.
bool PollFor(int fd, short events, int timeout_ms) {
  pollfd p{fd, events, 0};
  return poll(&p, 1, timeout_ms) > 0;
}

// A loopback TCP connection to PORT, non-blocking; -1 when it cannot be made.
int ConnectNonBlocking(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(std::uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 && errno != EINPROGRESS) {
    close(fd);
    return -1;
  }
  return fd;
}

// Idle connections and clients that send their request a header line at a time (slowloris) held
// every thread of the server's pool, each waiting for the rest of its request, the read timeout
// counted afresh for every line: the page went unanswered while they lasted (about 20 s for 400
// idle ones, for ever for 24 trickling ones). Now a connection holds no thread until its request
// head is complete, and each head must arrive within kLiveViewHeadSeconds however it trickles:
// with 400 idle and 24 trickling connections open the page is answered, and every one of them is
// then closed by the server. Waits are bounded polls, each round of which sends every trickling
// client one more header line (the trickle's pace is the test's pace, not a clock's).
TEST(LiveView, IdleAndTricklingConnectionsCannotStarveThePageAndAreCutInBoundedTime) {
  rlimit files{};
  getrlimit(RLIMIT_NOFILE, &files);
  files.rlim_cur = std::max<rlim_t>(files.rlim_cur, std::min<rlim_t>(files.rlim_max, 4096));
  setrlimit(RLIMIT_NOFILE, &files);
  auto source = std::make_unique<LiveSnapshotHistory>();
  LiveViewServer server(ServedPage{"<html>live</html>"}, *source, 0);
  constexpr int kIdle = 400, kTrickling = 24;
  std::vector<int> idle, trickling;
  for (int i = 0; i < kIdle; ++i) idle.push_back(ConnectNonBlocking(server.port()));
  for (int i = 0; i < kTrickling; ++i) trickling.push_back(ConnectNonBlocking(server.port()));
  for (const int fd : idle) ASSERT_GE(fd, 0);
  for (const int fd : trickling) ASSERT_GE(fd, 0);
  int line = 0;
  const auto trickle = [&] {
    for (const int fd : trickling) {
      const std::string text = line == 0 ? "GET / HTTP/1.1\r\n" : "X-Line-" + std::to_string(line) + ": 1\r\n";
      send(fd, text.data(), text.size(), MSG_NOSIGNAL);  // fails once the server closed it
    }
    ++line;
  };
  trickle();

  // The page, while they all are open: answered while the trickling clients still trickle (they
  // never finish) and before the idle ones could have timed out a pool-full at a time (20 s); the
  // 10 s bound is a hang guard.
  const auto guard = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  const int page = ConnectNonBlocking(server.port());
  ASSERT_GE(page, 0);
  const std::string get = "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  while (!PollFor(page, POLLOUT, 100) && std::chrono::steady_clock::now() < guard) trickle();
  ASSERT_EQ(send(page, get.data(), get.size(), MSG_NOSIGNAL), ssize_t(get.size()));
  std::string reply;
  char buffer[4096];
  while (reply.find("</html>") == std::string::npos && std::chrono::steady_clock::now() < guard) {
    if (!PollFor(page, POLLIN, 100)) {
      trickle();
      continue;
    }
    const ssize_t n = recv(page, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    reply.append(buffer, std::size_t(n));
  }
  close(page);
  EXPECT_EQ(reply.rfind("HTTP/1.1 200", 0), 0u) << reply;
  EXPECT_NE(reply.find("<html>live</html>"), std::string::npos) << reply;

  // Every idle and trickling connection is closed by the server (the trickling ones while still
  // sending): each within its head deadline of kLiveViewHeadSeconds, all within a 5 times longer
  // hang guard.
  std::vector<int> open = idle;
  open.insert(open.end(), trickling.begin(), trickling.end());
  const auto close_guard = std::chrono::steady_clock::now() + std::chrono::seconds(5 * kLiveViewHeadSeconds);
  while (!open.empty() && std::chrono::steady_clock::now() < close_guard) {
    std::vector<pollfd> polled;
    for (const int fd : open) polled.push_back(pollfd{fd, POLLIN, 0});
    if (poll(polled.data(), polled.size(), 100) == 0) trickle();
    std::vector<int> still;
    for (std::size_t k = 0; k < open.size(); ++k) {
      const ssize_t n = (polled[k].revents != 0) ? recv(open[k], buffer, sizeof buffer, MSG_DONTWAIT) : -1;
      if (n == 0 || (n < 0 && polled[k].revents != 0 && errno != EAGAIN)) {
        close(open[k]);
      } else {
        still.push_back(open[k]);
      }
    }
    open = std::move(still);
  }
  EXPECT_TRUE(open.empty()) << open.size() << " connections still open after " << 5 * kLiveViewHeadSeconds << " s";
  for (const int fd : open) close(fd);
}

// Contact marks of every point: in contact on odd cycles, clear on even ones.
class CycleParityModel final : public ContactModel {
 public:
  std::string_view name() const override { return "parity"; }
  ContactResult Evaluate(const ContactQuery&) override { return {}; }
  void Reset() override {}
  int PointStates(const ContactQuery& q, std::span<const std::int32_t> points, PointState* out) override {
    for (std::size_t k = 0; k < points.size(); ++k) out[k] = q.cycle % 2 ? PointState::kInContact : PointState::kClear;
    return int(points.size());
  }
};

// Marks go out at most once per MARKS_EVERY_CYCLES cycles of the sweeps (session time), and keep
// going out as the session's cycles advance. The client plays the session: on each snapshot
// it receives, it runs four more cycles (a sweep each) and publishes the snapshot of the last.
// A stream looks for marks right after sending a snapshot at least 10 cycles after the last
// marks, when the client may have run one more round: each gap is 10 to 17 cycles.
TEST(LiveView, StreamSendsMarksAtMostOncePerMarksCycles) {
  auto source = std::make_unique<LiveSnapshotHistory>();
  ContactPointMarks marks({0, 1, 2}, 3);
  PointMarksFeed feed(marks);
  CycleParityModel model;
  constexpr std::int64_t kMarksEvery = 10;
  LiveViewServer server(ServedPage{"<html></html>"}, *source, 0, &feed, kMarksEvery);
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(60, 0);  // a hang guard only
  std::int64_t cycle = 0;
  const auto run_to = [&](std::int64_t last) {
    for (ContactQuery q; cycle <= last; ++cycle) {
      q.cycle = cycle;
      marks.Update(model, q, cycle);
    }
    LiveSnapshot s;
    s.cycle = last;
    source->Publish(s);
  };
  run_to(0);
  StreamEvents events;
  client.Get("/stream", [&](const char* data, std::size_t n) {
    const std::size_t before = events.snapshots.size();
    events.Add(data, n);
    if (events.snapshots.size() > before) {
      const std::int64_t c = events.snapshots.back()["cycle"].get<std::int64_t>();
      if (c >= 48) return false;
      run_to(c + 4);
    }
    return true;
  });
  ASSERT_GE(events.marks.size(), 3u) << "marks by cycle 4, and at most 17 cycles after each";
  for (std::size_t k = 0; k < events.marks.size(); ++k) {
    const nlohmann::json& m = events.marks[k];
    EXPECT_EQ(m["points"], 3);
    EXPECT_EQ(m["first_cycle"], m["last_cycle"]);
    const std::int64_t c = m["last_cycle"].get<std::int64_t>();
    EXPECT_EQ(m["in_contact"], c % 2 ? 3 : 0);
    if (k == 0) {
      EXPECT_LE(c, 4);
    } else {
      const std::int64_t gap = c - events.marks[k - 1]["last_cycle"].get<std::int64_t>();
      EXPECT_GE(gap, kMarksEvery) << "marks " << k;
      EXPECT_LE(gap, kMarksEvery + 7) << "marks " << k;
    }
  }
  server.Stop();
}

// The session log's rows by t (its first column, "%.6f").
std::map<std::string, std::vector<double>> LogRows(const std::filesystem::path& file, std::vector<std::string>* header) {
  std::istringstream in(ReadWholeFile(file));
  std::map<std::string, std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header->empty()) {
      *header = SplitCsvLine(line);
      continue;
    }
    const std::vector<std::string> cells = SplitCsvLine(line);
    std::vector<double> v;
    for (const std::string& c : cells) v.push_back(std::strtod(c.c_str(), nullptr));
    rows[cells[0]] = v;
  }
  return rows;
}

// A 2-second session with --view-wait: it starts once this test opened the stream, the
// stream sends every snapshot the session took (one per 20 cycles, cycle 0 first) and, when the
// session ends, the rest and a clean end. Every snapshot and every contact marks event is then
// checked against the session's log. The session runs at 1 kHz in real time, but what the
// test checks depends only on its cycles: how fast the test, the session's consumer and the
// stream's thread run changes nothing.
TEST(LiveView, SessionStreamMatchesItsLog) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string cli = CONTACTLAB_CLI;
  const std::string command = cli + " session " + (dir / "scene.yaml").string() + " --cache " +
                              (dir / "cache").string() + " --device sim:circle:0.004:1 --touch 0.001 --duration 2 " +
                              "--no-realtime --quiet --view --view-wait --log " + (dir / "log.csv").string() + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  std::array<char, 4096> buf;
  int port = 0;
  while (port == 0 && std::fgets(buf.data(), int(buf.size()), pipe)) {
    output += buf.data();
    const std::string line = buf.data();
    const std::string prefix = "view: http://127.0.0.1:";
    if (line.rfind(prefix, 0) == 0) port = std::atoi(line.c_str() + prefix.size());
  }
  ASSERT_GT(port, 0) << output;

  // The page: the viewer with the scene's data and the live stream's address.
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(60, 0);  // a hang guard only
  auto page = client.Get("/");
  ASSERT_TRUE(page) << output;
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("\"live\":{"), std::string::npos);
  // three.js and the viewer's modules are files beside the page (the modules the entry
  // imports, such as replay.js, too), each served as JavaScript.
  EXPECT_NE(page->body.find("<script src=\"three/three.min.js\"></script>"), std::string::npos);
  EXPECT_NE(page->body.find("<script src=\"three/OrbitControls.js\"></script>"), std::string::npos);
  EXPECT_NE(page->body.find("<script type=\"module\" src=\"viewer/main.js\"></script>"), std::string::npos);
  for (const std::string path : {"three/three.min.js", "three/OrbitControls.js", "viewer/main.js", "viewer/replay.js"}) {
    const auto script = client.Get("/" + path);
    ASSERT_TRUE(script) << path;
    EXPECT_EQ(script->status, 200) << path;
    EXPECT_EQ(script->get_header_value("Content-Type"), "text/javascript; charset=utf-8") << path;
  }
  EXPECT_NE(client.Get("/three/OrbitControls.js")->body.find("THREE.OrbitControls"), std::string::npos);

  // The pointshell points the page draws (all of them: the shell is small).
  const std::string data_start = "<script type=\"application/json\" id=\"contactlab-data\">";
  const std::size_t data_at = page->body.find(data_start) + data_start.size();
  const nlohmann::json data =
      nlohmann::json::parse(page->body.substr(data_at, page->body.find("</script>", data_at) - data_at));
  const int drawn = data["pointshell"]["points"].get<int>();
  ASSERT_EQ(data["pointshell"]["kept"], data["pointshell"]["total"]);

  // The whole stream: opening it starts the session; it ends when the session does.
  StreamEvents stream;
  const auto streamed = client.Get("/stream", [&](const char* data, std::size_t n) {
    stream.Add(data, n);
    return true;
  });
  while (std::fgets(buf.data(), int(buf.size()), pipe)) output += buf.data();
  const int status = ::pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  ASSERT_TRUE(streamed && streamed->status == 200) << "the stream did not end cleanly\n" << output;
  const std::vector<nlohmann::json>& events = stream.snapshots;
  const std::vector<nlohmann::json>& marks = stream.marks;

  // The log's rows are the cycles in order when the consumer dropped none.
  ASSERT_NE(output.find("records dropped by the log consumer: 0"), std::string::npos) << output;
  std::vector<std::string> header;
  const auto rows = LogRows(dir / "log.csv", &header);
  const std::size_t cycles = rows.size();
  ASSERT_GT(cycles, 100u) << output;

  // Every snapshot of the session, once and in order: cycles 0, 20, 40, ... to the last.
  ASSERT_EQ(events.size(), (cycles - 1) / 20 + 1) << cycles << " cycles";
  for (std::size_t i = 0; i < events.size(); ++i) ASSERT_EQ(events[i]["cycle"].get<long>(), long(20 * i)) << i;
  // Each is a later moment of the session than the one before (t is the cycle's clock, so only
  // its order is checked here: how many fall in a wall-clock second depends on the machine).
  for (std::size_t i = 1; i < events.size(); ++i) {
    ASSERT_GT(events[i]["t"].get<double>(), events[i - 1]["t"].get<double>()) << i;
  }

  // Each snapshot is the log's row of its cycle: haptic body pose, device pose, force.
  auto col = [&](const char* name) { return int(std::find(header.begin(), header.end(), name) - header.begin()); };
  const int body = col("body_x"), device = col("x"), force = col("force_x"), contacts = col("points_in_contact");
  ASSERT_LT(body, int(header.size()));
  int in_contact = 0;
  double moved = 0;
  for (const nlohmann::json& e : events) {
    char t[32];
    std::snprintf(t, sizeof t, "%.6f", e["t"].get<double>());
    const auto it = rows.find(t);
    ASSERT_NE(it, rows.end()) << "no log row at t = " << t;
    ASSERT_EQ(std::distance(rows.begin(), it), e["cycle"].get<long>()) << "t = " << t;  // t has a fixed width: in order
    const std::vector<double>& r = it->second;
    for (int k = 0; k < 7; ++k) {
      EXPECT_NEAR(e["body"][k].get<double>(), r[body + k], 1e-8) << "t = " << t << ", body " << k;
      EXPECT_NEAR(e["device"][k].get<double>(), r[device + k], 1e-8) << "t = " << t << ", device " << k;
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(e["force"][k].get<double>(), r[force + k], 1e-5 * (1 + std::abs(r[force + k]))) << "t = " << t;
    }
    EXPECT_EQ(e["contacts"].get<int>(), int(r[contacts]));
    if (e["contacts"].get<int>() > 0) ++in_contact;
    moved = std::max(moved, std::abs(e["device"][0].get<double>() - events.front()["device"][0].get<double>()));
  }
  EXPECT_GT(in_contact, 0) << "the hand never pressed the plate into the ball";
  EXPECT_GT(moved, 1e-3) << "the device did not move";

  // Marks: at least one (a stream sends the newest before it ends), at most one per 67 cycles
  // of session time (15 a second at 1 kHz); every drawn point marked, the counts those of the
  // 2-bit states, and (the shell fits in one chunk, so a sweep is one cycle) the points marked
  // in contact as many as the log's points in contact at that cycle.
  std::vector<double> contacts_by_cycle;
  for (const auto& [t, r] : rows) contacts_by_cycle.push_back(r[contacts]);  // t has a fixed width: in order
  ASSERT_GE(marks.size(), 1u);
  int marks_in_contact = 0;
  for (std::size_t k = 0; k < marks.size(); ++k) {
    const nlohmann::json& m = marks[k];
    EXPECT_EQ(m["points"].get<int>(), drawn);
    const std::string packed = Base64Decode(m["states"].get<std::string>(), "marks");
    ASSERT_EQ(int(packed.size()), (drawn + 3) / 4);
    int counts[4] = {0, 0, 0, 0};
    for (int i = 0; i < drawn; ++i) ++counts[(std::uint8_t(packed[i / 4]) >> (2 * (i % 4))) & 3];
    EXPECT_EQ(counts[3], 0);
    EXPECT_EQ(counts[2], m["in_contact"].get<int>());
    EXPECT_EQ(counts[1] + counts[2], m["evaluated"].get<int>());
    ASSERT_EQ(m["first_cycle"], m["last_cycle"]);
    const long cycle = m["last_cycle"].get<long>();
    ASSERT_LT(cycle, long(contacts_by_cycle.size()));
    EXPECT_EQ(counts[2], int(contacts_by_cycle[std::size_t(cycle)])) << "cycle " << cycle;
    if (k > 0) {
      EXPECT_GE(cycle - marks[k - 1]["last_cycle"].get<long>(), 67) << "marks " << k;
    }
    marks_in_contact += counts[2] > 0;
  }
  EXPECT_GT(marks_in_contact, 0);
}

}  // namespace
}  // namespace contactlab
