// The live view's HTTP connections: request heads gathered by one gate thread, complete
// requests answered by a fixed pool of workers (request_gate.h).
#include "view/request_gate.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <optional>

#include "util/error.h"

namespace contactlab {
namespace {

using Clock = std::chrono::steady_clock;

// Milliseconds from now to DEADLINE, at least 0 and at most CAP.
int MillisecondsUntil(Clock::time_point deadline, std::chrono::milliseconds cap) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return int(std::clamp(left, std::chrono::milliseconds(0), cap).count());
}

// Waits up to TIMEOUT_MS for EVENTS on FD; true when they came.
bool PollFor(int fd, short events, int timeout_ms) {
  pollfd p{fd, events, 0};
  for (;;) {
    const int n = ::poll(&p, 1, timeout_ms);
    if (n < 0 && errno == EINTR) continue;
    return n > 0 && (p.revents & (events | POLLHUP | POLLERR)) != 0;
  }
}

// Where a complete request head ends in TEXT (after its blank line), or npos.
std::size_t HeadEnd(std::string_view text) {
  const std::size_t crlf = text.find("\r\n\r\n"), lf = text.find("\n\n");
  if (crlf == std::string_view::npos && lf == std::string_view::npos) return std::string_view::npos;
  return std::min(crlf == std::string_view::npos ? text.size() : crlf + 4, lf == std::string_view::npos ? text.size() : lf + 2);
}

// The target of the request line that HEAD starts with ("/stream"), without its query.
std::string_view RequestTarget(std::string_view head) {
  const std::size_t start = head.find(' ');
  if (start == std::string_view::npos) return {};
  const std::size_t end = head.find_first_of(" ?\r\n", start + 1);
  return head.substr(start + 1, end == std::string_view::npos ? std::string_view::npos : end - start - 1);
}

// A whole answer the gate sends itself, closing the connection: STATUS ("416 Range Not
// Satisfiable") and a plain-text BODY, its length counted.
std::string GateAnswer(const char* status, const std::string& body) {
  return std::string("HTTP/1.1 ") + status + "\r\nConnection: close\r\nContent-Type: text/plain\r\nContent-Length: " +
         std::to_string(body.size()) + "\r\n\r\n" + body;
}

void AddressOf(const sockaddr_storage& address, std::string& ip, int& port);

// The local port of the connection FD (the server's), 0 when it cannot be read.
int LocalPort(int fd) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) return 0;
  std::string ip;
  int port = 0;
  AddressOf(address, ip, port);
  return port;
}

void AddressOf(const sockaddr_storage& address, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = "";
  if (address.ss_family == AF_INET) {
    const auto& a = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &a.sin_addr, text, sizeof text);
    port = ntohs(a.sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto& a = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &a.sin6_addr, text, sizeof text);
    port = ntohs(a.sin6_port);
  }
  ip = text;
}

// A worker's view of one connection for httplib: the bytes the gate read first, then the
// socket, each read and write waiting at most the I/O timeout and none past the deadline.
class GateStream final : public httplib::Stream {
 public:
  GateStream(int fd, std::string head, std::chrono::milliseconds io_timeout, std::optional<Clock::time_point> deadline)
      : fd_(fd), head_(std::move(head)), io_timeout_(io_timeout), deadline_(deadline) {}

  bool is_readable() const override { return at_ < head_.size() || PollFor(fd_, POLLIN, WaitMs()); }
  // Writable within the timeout, and the peer still there.
  bool is_writable() const override {
    if (!PollFor(fd_, POLLOUT, WaitMs())) return false;
    char byte;
    const ssize_t n = ::recv(fd_, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
    return n > 0 || (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR));
  }
  ssize_t read(char* ptr, size_t size) override {
    if (at_ < head_.size()) {
      const std::size_t n = std::min(size, head_.size() - at_);
      std::memcpy(ptr, head_.data() + at_, n);
      at_ += n;
      return ssize_t(n);
    }
    for (;;) {
      if (!PollFor(fd_, POLLIN, WaitMs())) return -1;
      const ssize_t n = ::recv(fd_, ptr, size, MSG_DONTWAIT);
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) continue;
      return n;
    }
  }
  ssize_t write(const char* ptr, size_t size) override {
    for (;;) {
      if (!PollFor(fd_, POLLOUT, WaitMs())) return -1;
      const ssize_t n = ::send(fd_, ptr, size, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) continue;
      return n;
    }
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (::getpeername(fd_, reinterpret_cast<sockaddr*>(&address), &length) == 0) AddressOf(address, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) == 0) AddressOf(address, ip, port);
  }
  socket_t socket() const override { return fd_; }

  // What the gate read that httplib did not (a pipelined next request).
  std::string TakeUnread() { return head_.substr(std::min(at_, head_.size())); }

 private:
  // How long one wait may last: the I/O timeout, cut at the deadline.
  int WaitMs() const {
    return deadline_ ? MillisecondsUntil(*deadline_, io_timeout_) : int(io_timeout_.count());
  }

  int fd_;
  std::string head_;
  std::size_t at_ = 0;
  std::chrono::milliseconds io_timeout_;
  std::optional<Clock::time_point> deadline_;
};

// A task queue that runs each task at once on the calling (listen) thread: the task only hands
// the socket to the gate.
class RunAtOnce final : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override {}
};

}  // namespace

std::string_view RequestHeader(std::string_view head, std::string_view name) {
  const std::size_t end = HeadEnd(head);
  if (end != std::string_view::npos) head = head.substr(0, end);
  std::size_t at = head.find('\n');  // past the request line
  while (at != std::string_view::npos && at + 1 < head.size()) {
    const std::size_t start = at + 1;
    at = head.find('\n', start);
    std::string_view line = head.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::size_t colon = line.find(':');
    if (colon != name.size()) continue;
    bool same = true;
    for (std::size_t k = 0; k < colon && same; ++k) {
      same = std::tolower(static_cast<unsigned char>(line[k])) == std::tolower(static_cast<unsigned char>(name[k]));
    }
    if (!same) continue;
    std::string_view value = line.substr(colon + 1);
    while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.remove_prefix(1);
    while (!value.empty() && (value.back() == ' ' || value.back() == '\t')) value.remove_suffix(1);
    return value;
  }
  return {};
}

const char* ScreenRequest(std::string_view head, int port) {
  static const std::string kMisdirected =
      GateAnswer("421 Misdirected Request", "the live view answers requests for its loopback host\n");
  static const std::string kOneRange = GateAnswer("416 Range Not Satisfiable", "the live view answers one range per request\n");
  const std::string_view host = RequestHeader(head, "Host");
  if (!host.empty()) {
    const std::string with_port = ":" + std::to_string(port);
    bool ours = false;
    for (const std::string_view name : {"127.0.0.1", "localhost", "[::1]"}) {
      ours = ours || host == name || host == std::string(name) + with_port;
    }
    if (!ours) return kMisdirected.c_str();
  }
  if (RequestHeader(head, "Range").find(',') != std::string_view::npos) return kOneRange.c_str();
  return nullptr;
}

std::string RequestPath(std::string_view head) {
  return httplib::detail::decode_url(std::string(RequestTarget(head)), false);  // as the router decodes it
}

GatedHttpServer::GatedHttpServer(const RequestGateLimits& limits, std::function<bool(std::string_view)> long_lived)
    : limits_(limits), long_lived_(std::move(long_lived)) {
  if (limits_.workers < 1 || limits_.max_waiting < 1 || limits_.max_requests < 1)
    Fail("live view", "the request gate needs workers, waiting connections and requests per connection");
  wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) Fail("live view", std::string("cannot make an eventfd: ") + std::strerror(errno));
  new_task_queue = [] { return new RunAtOnce; };
  // What httplib says in its Keep-Alive header.
  set_keep_alive_timeout(std::max<time_t>(1, time_t(limits_.head_timeout.count() / 1000)));
  set_keep_alive_max_count(std::size_t(limits_.max_requests));
  gate_ = std::thread([this] { GateMain(); });
  for (int i = 0; i < limits_.workers; ++i) workers_.emplace_back([this] { WorkerMain(); });
}

GatedHttpServer::~GatedHttpServer() {
  StopGate();
  ::close(wake_fd_);
}

void GatedHttpServer::StopGate() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
  ready_changed_.notify_all();
  if (gate_.joinable()) gate_.join();
  for (std::thread& worker : workers_)
    if (worker.joinable()) worker.join();
  std::lock_guard<std::mutex> lock(mutex_);
  for (const Connection& c : arriving_) Close(c.fd);
  for (const Connection& c : ready_) Close(c.fd);
  arriving_.clear();
  ready_.clear();
}

void GatedHttpServer::WidenBacklog() {
  const socket_t sock = svr_sock_;
  if (sock >= 0) ::listen(sock, SOMAXCONN);
}

bool GatedHttpServer::process_and_close_socket(socket_t sock) {
  ::fcntl(sock, F_SETFL, ::fcntl(sock, F_GETFL) | O_NONBLOCK);
  Wait(Connection{sock, {}, Clock::now() + limits_.head_timeout, 0});
  return true;
}

// Hands CONNECTION to the gate (closed at once when the server stops).
void GatedHttpServer::Wait(Connection connection) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stopping_) {
      arriving_.push_back(std::move(connection));
      connection.fd = -1;
    }
  }
  if (connection.fd >= 0) Close(connection.fd);
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(wake_fd_, &one, sizeof one);
}

void GatedHttpServer::Close(int fd) {
  ::shutdown(fd, SHUT_RDWR);
  ::close(fd);
}

bool GatedHttpServer::ReadHead(Connection& c) {
  char buffer[4096];
  while (c.head.size() <= limits_.max_head_bytes) {
    const ssize_t n = ::recv(c.fd, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n > 0) {
      c.head.append(buffer, std::size_t(n));
      continue;
    }
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);  // 0: the peer left
  }
  static const std::string too_large = GateAnswer("431 Request Header Fields Too Large", "");
  [[maybe_unused]] const ssize_t n = ::send(c.fd, too_large.data(), too_large.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
  return false;
}

// The gate: waits for the heads of every waiting connection at once; a complete one goes to the
// workers, one past its deadline or its size, or whose peer left, is closed.
void GatedHttpServer::GateMain() {
  std::vector<Connection> waiting;
  std::vector<pollfd> polled;
  for (;;) {
    // New connections (and ones back from a worker), and whether to stop.
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stopping_) break;
      for (Connection& c : arriving_) waiting.push_back(std::move(c));
      arriving_.clear();
    }
    // Past the bound, the oldest waiting connections are closed.
    if (int(waiting.size()) > limits_.max_waiting) {
      std::sort(waiting.begin(), waiting.end(), [](const Connection& a, const Connection& b) { return a.deadline < b.deadline; });
      const std::size_t excess = waiting.size() - std::size_t(limits_.max_waiting);
      for (std::size_t k = 0; k < excess; ++k) Close(waiting[k].fd);
      waiting.erase(waiting.begin(), waiting.begin() + std::ptrdiff_t(excess));
    }
    // Complete heads go to the workers; expired connections are closed.
    std::vector<Connection> still;
    Clock::time_point next = Clock::now() + limits_.head_timeout;
    for (Connection& c : waiting) {
      if (HeadEnd(c.head) != std::string_view::npos) {
        std::lock_guard<std::mutex> lock(mutex_);
        ready_.push_back(std::move(c));
        ready_changed_.notify_one();
      } else if (Clock::now() >= c.deadline) {
        Close(c.fd);
      } else {
        next = std::min(next, c.deadline);
        still.push_back(std::move(c));
      }
    }
    waiting = std::move(still);
    // Wait for bytes, a new connection or the nearest deadline.
    polled.assign(1, pollfd{wake_fd_, POLLIN, 0});
    for (const Connection& c : waiting) polled.push_back(pollfd{c.fd, POLLIN, 0});
    const int n = ::poll(polled.data(), polled.size(), MillisecondsUntil(next, limits_.head_timeout) + 1);
    if (n <= 0) continue;
    if (polled[0].revents != 0) {
      std::uint64_t count;
      [[maybe_unused]] const ssize_t r = ::read(wake_fd_, &count, sizeof count);
    }
    std::vector<Connection> open;
    for (std::size_t k = 0; k < waiting.size(); ++k) {
      if (polled[k + 1].revents != 0 && !ReadHead(waiting[k])) {
        Close(waiting[k].fd);
      } else {
        open.push_back(std::move(waiting[k]));
      }
    }
    waiting = std::move(open);
  }
  for (const Connection& c : waiting) Close(c.fd);
}

void GatedHttpServer::WorkerMain() {
  for (;;) {
    Connection c;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_changed_.wait(lock, [&] { return stopping_ || !ready_.empty(); });
      if (ready_.empty()) return;  // stopping, nothing left to answer
      c = std::move(ready_.front());
      ready_.pop_front();
    }
    Answer(std::move(c));
  }
}

// Answers the request at the start of C's head (httplib parses, routes and writes it); a
// kept-alive connection then waits at the gate for its next request.
void GatedHttpServer::Answer(Connection c) {
  if (const char* refusal = ScreenRequest(c.head, LocalPort(c.fd))) {
    [[maybe_unused]] const ssize_t n = ::send(c.fd, refusal, std::strlen(refusal), MSG_DONTWAIT | MSG_NOSIGNAL);
    Close(c.fd);
    return;
  }
  const bool long_lived = long_lived_ && long_lived_(RequestPath(c.head));
  GateStream stream(c.fd, std::move(c.head), limits_.io_timeout,
                    long_lived ? std::nullopt : std::optional(Clock::now() + limits_.response_timeout));
  ++c.requests;
  bool stopping;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping = stopping_;
  }
  const bool close = c.requests >= limits_.max_requests || stopping;
  bool connection_closed = false;
  const bool ok = process_request(stream, close, connection_closed, nullptr);
  if (!ok || close || connection_closed) {
    Close(c.fd);
    return;
  }
  Wait(Connection{c.fd, stream.TakeUnread(), Clock::now() + limits_.head_timeout, c.requests});
}

}  // namespace contactlab
