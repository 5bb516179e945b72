#pragma once
// The monitor's accept path: every connection waits here, on one thread
// polling them all, until its whole request has arrived (head and announced
// body, web/http/http_head.h) and only then takes a serving thread. A client that
// trickles its request (slowloris) or never finishes it holds a slot of this
// poll set until the head deadline, never a thread; the slots are capped per
// client address and in all, past which a connection is answered at once.
// Over TLS the gate cannot read the request: it waits for the client's first
// bytes and the serving thread reads the rest before the same deadline.
#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "web/http/bounded_pool.h"
#include "web/http/http_head.h"

namespace wavebake::web {

struct GateOptions {
  int threads = 16;                    // serving threads (event streams are capped below them)
  size_t max_queued = 64;              // complete requests waiting for a thread; then 503
  size_t max_waiting = 256;            // connections whose request is still arriving; then 503
  size_t max_waiting_per_client = 32;  // the same, per client address; then 429
  std::chrono::milliseconds head_deadline{3000};  // from accept to a complete request; then 408
  bool tls = false;
  HeadLimits limits{};
};

class HttpGate {
 public:
  // Takes `listen_fd` (bound and listening). `serve(fd, deadline)` answers
  // one request (its reads end at `deadline`) and closes fd.
  using Serve = std::function<void(int fd, std::chrono::steady_clock::time_point deadline)>;
  HttpGate(int listen_fd, GateOptions options, Serve serve);
  ~HttpGate();  // Stop()

  // Stops accepting, closes the waiting connections, then lets the serving
  // threads finish what they serve (the caller ends long responses first).
  void Stop();

 private:
  using Clock = std::chrono::steady_clock;
  struct Waiting {
    int fd;
    std::string client;
    Clock::time_point deadline;
    size_t received = 0;
    Clock::time_point quiet_until{};  // no new bytes last time: not polled before
  };
  void Run();
  void Accept();
  // Looks at what `w` has received; true when it left the waiting set.
  bool Examine(Waiting& w, bool hung_up);
  void Answer(int fd, int status, const std::string& reason);
  void Forget(const Waiting& w);

  const GateOptions options_;
  int listen_fd_;
  int wake_fd_;
  std::vector<Waiting> waiting_;
  std::map<std::string, size_t> per_client_;
  std::vector<char> peek_;
  BoundedPool pool_;
  std::thread thread_;
};

}  // namespace wavebake::web
