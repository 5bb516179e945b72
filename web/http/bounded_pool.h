#pragma once
// A fixed set of threads serving accepted connections from a queue of
// bounded length: past it, Offer() says no at once and the caller answers
// 503, instead of the connection waiting unseen behind a queue without end.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace wavebake::web {

class BoundedPool {
 public:
  struct Connection {
    int fd;
    std::chrono::steady_clock::time_point deadline;  // for reading its request
  };
  // `serve` answers the connection and closes its fd.
  BoundedPool(int threads, size_t max_queued, std::function<void(Connection)> serve);
  ~BoundedPool();  // Stop()

  bool Offer(Connection c);
  // Lets running connections finish, closes the queued ones, joins.
  void Stop();

 private:
  void Run();

  const size_t max_queued_;
  const std::function<void(Connection)> serve_;
  std::mutex mu_;
  std::condition_variable ready_;
  std::deque<Connection> queue_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace wavebake::web
