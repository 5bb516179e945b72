#include "web/http/bounded_pool.h"

#include <unistd.h>

namespace wavebake::web {

BoundedPool::BoundedPool(int threads, size_t max_queued, std::function<void(Connection)> serve)
    : max_queued_(max_queued), serve_(std::move(serve)) {
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { Run(); });
}

BoundedPool::~BoundedPool() { Stop(); }

bool BoundedPool::Offer(Connection c) {
  {
    std::lock_guard lock(mu_);
    if (stopping_ || queue_.size() >= max_queued_) return false;
    queue_.push_back(c);
  }
  ready_.notify_one();
  return true;
}

void BoundedPool::Stop() {
  {
    std::lock_guard lock(mu_);
    if (stopping_ && threads_.empty()) return;
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
  for (const Connection& c : queue_) ::close(c.fd);
  queue_.clear();
}

void BoundedPool::Run() {
  for (;;) {
    Connection c{};
    {
      std::unique_lock lock(mu_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      c = queue_.front();
      queue_.pop_front();
    }
    serve_(c);
  }
}

}  // namespace wavebake::web
