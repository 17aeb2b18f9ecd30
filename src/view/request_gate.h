// An HTTP server (cpp-httplib's request parsing, routing and responses) in which a connection
// holds a worker thread only while a complete request is answered. httplib alone gives each
// accepted connection a thread of its pool from the start, which then waits for the request,
// the read timeout counted afresh for every byte: idle connections, or clients that send their
// header a line at a time, hold every thread and starve the page. Here one gate thread waits for
// the request heads of all open connections at once (poll, non-blocking reads), each head within
// one deadline and a size bound; a connection that sends nothing, sends its head too slowly or
// too large is closed by the gate. A complete request goes to a fixed pool of workers; after the
// response a kept-alive connection goes back to the gate for its next request.
//
// Include after Eigen's headers: httplib.h brings <resolv.h>, whose macro _res breaks Eigen's.
#pragma once

#include <httplib.h>

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace contactlab {

// The target of the request line HEAD starts with, without its query and percent-decoded as
// httplib decodes a path before routing it ("GET /%73tream HTTP/1.1" gives "/stream"), so that
// what the gate takes for a long-lived target is what the router will answer.
std::string RequestPath(std::string_view head);

// The value of header NAME (case-insensitive) in the request head HEAD, without surrounding
// blanks; empty when absent.
std::string_view RequestHeader(std::string_view head, std::string_view name);

// What the gate answers itself, before httplib sees a request, or nullptr to let it through:
// a Host that is not this loopback server (127.0.0.1, localhost or [::1], with PORT when it names
// one) gets 421, so a web page cannot reach the server through DNS rebinding; a Range of more
// than one part gets 416, since httplib would build the whole multipart answer in memory
// (2,000 parts of an 8 KB header made a 1 GB answer). A request without Host (HTTP/1.0) passes.
const char* ScreenRequest(std::string_view head, int port);

struct RequestGateLimits {
  int workers = 20;                // threads answering complete requests
  int max_waiting = 256;           // connections waiting for a request head; past it the oldest is closed
  std::chrono::milliseconds head_timeout{2000};  // a whole request head, from the connection or the last response
  std::size_t max_head_bytes = 16384;            // a longer head is answered 431 and closed
  int max_requests = 100;                        // requests per connection
  std::chrono::milliseconds io_timeout{2000};    // each read or write once a worker answers
  std::chrono::milliseconds response_timeout{10000};  // a whole response, except a long-lived one
};

class GatedHttpServer : public httplib::Server {
 public:
  // LONG_LIVED(target) is true for request targets whose response has no time limit but the per-write
  // one (an event stream, bounded in number by its handler). Starts the gate and the workers.
  GatedHttpServer(const RequestGateLimits& limits, std::function<bool(std::string_view target)> long_lived);
  ~GatedHttpServer() override;

  // After bind_to_port or bind_to_any_port: lets the listening socket queue as many connections
  // as the system allows (SOMAXCONN) instead of httplib's 5, so that a burst of connections waits
  // to be accepted by the gate rather than in TCP retransmissions.
  void WidenBacklog();

  // Closes every waiting connection and joins the gate and the workers (after stop() and the
  // end of listen_after_bind, so that no connection arrives any more). Idempotent.
  void StopGate();

 private:
  struct Connection {
    int fd = -1;
    std::string head;  // bytes read and not yet parsed (a request head, maybe more)
    std::chrono::steady_clock::time_point deadline;
    int requests = 0;  // answered so far
  };

  // httplib's listen thread hands every accepted socket here (through a task queue that runs
  // the task at once): it joins the gate's waiting connections.
  bool process_and_close_socket(socket_t sock) override;
  void Wait(Connection connection);
  void GateMain();
  // Reads what CONNECTION's socket holds (non-blocking); false when it is to be closed.
  bool ReadHead(Connection& connection);
  void WorkerMain();
  void Answer(Connection connection);
  void Close(int fd);

  RequestGateLimits limits_;
  std::function<bool(std::string_view)> long_lived_;
  int wake_fd_ = -1;  // eventfd: new connections or stopping
  std::mutex mutex_;  // guards the three below
  std::condition_variable ready_changed_;
  std::vector<Connection> arriving_;  // for the gate
  std::deque<Connection> ready_;      // complete requests, for the workers
  bool stopping_ = false;
  std::thread gate_;
  std::vector<std::thread> workers_;
};

}  // namespace contactlab
