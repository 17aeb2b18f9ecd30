// contactlab-udp-peer: plays the device side of the UDP haptic protocol (UDP_PROTOCOL.md) on
// loopback — sends manipulandum poses on a circle at a fixed rate and receives the wrenches the
// haptic loop (Barbič & James 2008, sec. 5) sends back. Optionally injects bad packets.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "haptics/udp_protocol.h"
#include "util/finite_options.h"

namespace {

std::int64_t NowNs() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace contactlab;
  CLI::App app{"Device side of the ContactLab UDP haptic protocol, on 127.0.0.1 only"};
  int host_port = 27016, listen_port = 0;
  double duration = 5.0, rate = 1000.0, radius = 0.02, period = 2.0;
  bool inject = false, quiet = false;
  app.add_option("--host-port", host_port, "port the ContactLab udp device listens on")->check(CLI::Range(1, 65535));
  app.add_option("--listen-port", listen_port, "this peer's port for wrench packets (0: any)")->check(CLI::Range(0, 65535));
  app.add_option("--duration", duration, "seconds to run")->check(CLI::PositiveNumber);
  app.add_option("--rate", rate, "pose packets per second")->check(CLI::Range(1.0, 20000.0));
  app.add_option("--radius", radius, "circle radius, metres")->check(CLI::Range(0.0, 1.0));
  app.add_option("--period", period, "seconds per revolution")->check(CLI::PositiveNumber);
  app.add_flag("--inject-faults", inject, "every 100th cycle also send a short, a corrupted, a duplicate and an old packet");
  app.add_flag("--quiet", quiet, "print only the summary");
  RequireFiniteNumbers(app);
  CLI11_PARSE(app, argc, argv);

  // Socket bound to loopback; poses go to 127.0.0.1:host_port.
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  if (fd < 0) {
    std::fprintf(stderr, "error: contactlab-udp-peer: cannot open a UDP socket: %s\n", std::strerror(errno));
    return 1;
  }
  sockaddr_in self{};
  self.sin_family = AF_INET;
  self.sin_port = htons(std::uint16_t(listen_port));
  self.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&self), sizeof(self)) != 0) {
    std::fprintf(stderr, "error: contactlab-udp-peer: cannot bind 127.0.0.1:%d: %s\n", listen_port, std::strerror(errno));
    return 1;
  }
  sockaddr_in host{};
  host.sin_family = AF_INET;
  host.sin_port = htons(std::uint16_t(host_port));
  host.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  auto send = [&](const std::uint8_t* data, std::size_t n) {
    ::sendto(fd, data, n, 0, reinterpret_cast<sockaddr*>(&host), sizeof(host));
  };

  // Main loop: one pose per period, drain wrench packets.
  const std::int64_t period_ns = std::int64_t(1e9 / rate);
  const std::int64_t t0 = NowNs();
  std::int64_t next = t0;
  std::uint64_t seq = 0, received = 0, bad = 0, last_wrench_seq = 0, reordered = 0;
  double max_force = 0;
  udp::PoseBytes bytes;
  udp::PosePacket prev;
  while (NowNs() - t0 < std::int64_t(duration * 1e9)) {
    const std::int64_t now = NowNs();
    const double t = 1e-9 * double(now - t0);
    udp::PosePacket p;
    p.sequence = ++seq;
    p.timestamp_ns = now;
    p.position[0] = radius * std::cos(2 * M_PI * t / period);
    p.position[1] = radius * std::sin(2 * M_PI * t / period);
    udp::EncodePose(p, &bytes);
    send(bytes.data(), bytes.size());
    if (inject && seq % 100 == 0 && seq > 1) {
      send(bytes.data(), 10);                      // short
      send(bytes.data(), bytes.size());            // duplicate
      udp::PoseBytes bad_bytes = bytes;
      bad_bytes[30] ^= 0x40;                       // corrupted payload (checksum fails)
      send(bad_bytes.data(), bad_bytes.size());
      udp::EncodePose(prev, &bad_bytes);           // out of order (older sequence)
      send(bad_bytes.data(), bad_bytes.size());
    }
    prev = p;
    std::uint8_t buf[256];
    for (;;) {
      const ssize_t n = ::recv(fd, buf, sizeof(buf), 0);
      if (n < 0) break;
      udp::WrenchPacket w;
      if (udp::DecodeWrench(buf, std::size_t(n), &w) != udp::DecodeStatus::kOk) {
        ++bad;
        continue;
      }
      ++received;
      if (w.sequence <= last_wrench_seq) ++reordered;
      last_wrench_seq = w.sequence;
      const double f = std::sqrt(w.force[0] * w.force[0] + w.force[1] * w.force[1] + w.force[2] * w.force[2]);
      max_force = std::max(max_force, f);
      if (!quiet && received % 1000 == 0)
        std::printf("t %.3f s  wrench #%llu  force (%.3f %.3f %.3f) N\n", t, (unsigned long long)w.sequence,
                    w.force[0], w.force[1], w.force[2]);
    }
    next += period_ns;
    const timespec ts{time_t(next / 1000000000), long(next % 1000000000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
  }
  std::printf("contactlab-udp-peer: sent %llu poses, received %llu wrenches (%llu malformed, %llu out of order), max |F| %.3f N\n",
              (unsigned long long)seq, (unsigned long long)received, (unsigned long long)bad,
              (unsigned long long)reordered, max_force);
  ::close(fd);
  return 0;
}
