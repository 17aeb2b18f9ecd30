// The live view of a session end to end: `contactlab session ... --view` on a free loopback
// port, its page and event stream read with httplib::Client while the session runs, and every
// streamed snapshot checked against the session's log row of the same cycle.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiment/result_csv.h"
#include "allocation_counter.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "view/page_encoding.h"
#include "view/latest_value.h"
#include "view/live_view_server.h"

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

TEST(LiveView, ServerStreamsTheNewestSnapshotOnLoopback) {
  LatestValue<LiveSnapshot> source;
  LiveViewServer server("<html>page</html>", source, 0, 100);
  ASSERT_GT(server.port(), 0);
  httplib::Client client("127.0.0.1", server.port());
  // Before the first snapshot: the page, and no snapshot.
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->body, "<html>page</html>");
  auto none = client.Get("/snapshot");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 204);
  LiveSnapshot s;
  s.t = 1.5;
  s.cycle = 1500;
  s.p_WH[2] = -0.25;
  s.contact_force[2] = 3.0;
  s.level_rendered = 2;
  source.Store(s);
  auto one = client.Get("/snapshot");
  ASSERT_TRUE(one);
  const nlohmann::json j = nlohmann::json::parse(one->body);
  EXPECT_EQ(j["cycle"], 1500);
  EXPECT_DOUBLE_EQ(j["body"][2].get<double>(), -0.25);
  EXPECT_DOUBLE_EQ(j["contact_force"][2].get<double>(), 3.0);
  EXPECT_EQ(j["level"], 2);
  // The stream sends it once as an event.
  std::string got;
  client.Get("/stream", [&](const char* data, std::size_t n) {
    got.append(data, n);
    return got.find("\n\n") == std::string::npos;
  });
  EXPECT_EQ(got.rfind("data: {\"t\":1.500000,\"cycle\":1500,", 0), 0u) << got;
  server.Stop();
  EXPECT_FALSE(client.Get("/"));
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

TEST(LiveView, SessionStreamMatchesItsLog) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  // Warm the cache first so the session starts at once.
  const std::string cli = CONTACTLAB_CLI;
  const std::string common = (dir / "scene.yaml").string() + " --cache " + (dir / "cache").string();
  ASSERT_EQ(std::system((cli + " contact " + common + " > /dev/null 2>&1").c_str()), 0);
  const std::string command = cli + " session " + common + " --device sim:circle:0.004:1 --touch 0.001 --duration 3 " +
                              "--no-realtime --quiet --view --log " + (dir / "log.csv").string() + " 2>&1";
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
  client.set_read_timeout(10, 0);
  auto page = client.Get("/");
  ASSERT_TRUE(page) << output;
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("\"live\":{"), std::string::npos);
  EXPECT_NE(page->body.find("THREE.OrbitControls"), std::string::npos);

  // The pointshell points the page draws (all of them: the shell is small).
  const std::string data_start = "<script type=\"application/json\" id=\"contactlab-data\">";
  const std::size_t data_at = page->body.find(data_start) + data_start.size();
  const nlohmann::json data =
      nlohmann::json::parse(page->body.substr(data_at, page->body.find("</script>", data_at) - data_at));
  const int drawn = data["pointshell"]["points"].get<int>();
  ASSERT_EQ(data["pointshell"]["kept"], data["pointshell"]["total"]);

  // One second of the stream: snapshots, and the contact marks of the drawn points.
  std::string buffer;
  std::vector<nlohmann::json> events, marks;
  client.Get("/stream", [&](const char* data, std::size_t n) {
    buffer.append(data, n);
    for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos;) {
      const std::string event = buffer.substr(0, end);
      buffer.erase(0, end + 2);
      const std::string marks_prefix = "event: marks\ndata: ";
      if (event.rfind(marks_prefix, 0) == 0) {
        marks.push_back(nlohmann::json::parse(event.substr(marks_prefix.size())));
        continue;
      }
      EXPECT_EQ(event.rfind("data: ", 0), 0u) << event;
      events.push_back(nlohmann::json::parse(event.substr(6)));
    }
    return events.size() < 50 || events.back()["t"].get<double>() - events.front()["t"].get<double>() < 1.0;
  });
  while (std::fgets(buf.data(), int(buf.size()), pipe)) output += buf.data();
  const int status = ::pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;

  // 30 to 60 snapshots a second, in order.
  ASSERT_GE(events.size(), 30u) << output;
  const double span = events.back()["t"].get<double>() - events.front()["t"].get<double>();
  const double rate = double(events.size() - 1) / span;
  EXPECT_GE(rate, 30.0);
  EXPECT_LE(rate, 60.0);
  for (std::size_t i = 1; i < events.size(); ++i) EXPECT_GT(events[i]["cycle"], events[i - 1]["cycle"]);

  // Each snapshot is the log's row of its cycle: haptic body pose, device pose, force.
  std::vector<std::string> header;
  const auto rows = LogRows(dir / "log.csv", &header);
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

  // Marks, 5 to 20 a second: every drawn point marked, the counts those of the 2-bit states,
  // and (the shell fits in one chunk, so a sweep is one cycle) the points marked in contact
  // are as many as the log's points in contact at that cycle. The log's rows are the cycles
  // in order when the consumer dropped none, which the snapshots' rows confirm.
  ASSERT_NE(output.find("records dropped by the log consumer: 0"), std::string::npos) << output;
  std::vector<double> contacts_by_cycle;
  for (const auto& [t, r] : rows) contacts_by_cycle.push_back(r[contacts]);  // t has a fixed width: in order
  for (const nlohmann::json& e : events) {
    char t[32];
    std::snprintf(t, sizeof t, "%.6f", e["t"].get<double>());
    ASSERT_EQ(std::distance(rows.begin(), rows.find(t)), e["cycle"].get<long>()) << "t = " << t;
  }
  EXPECT_GE(marks.size(), 5u);
  EXPECT_LE(double(marks.size()), 20.0 * (span + 0.2));
  int marks_in_contact = 0;
  for (const nlohmann::json& m : marks) {
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
    marks_in_contact += counts[2] > 0;
  }
  EXPECT_GT(marks_in_contact, 0);
}

}  // namespace
}  // namespace contactlab
