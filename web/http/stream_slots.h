#pragma once
// How many event streams may be open at once, in all and per client
// address: each holds a serving thread for as long as it lasts, so past the
// caps a stream is refused (503 in all, 429 for one client) and the page
// falls back to polling, rather than the streams taking every thread.
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace wavebake::web {

class StreamSlots {
 public:
  StreamSlots(int total, int per_client) : total_(total), per_client_(per_client) {}

  struct Grant {
    std::shared_ptr<void> slot;  // held while the stream lasts; null: refused
    int status = 0;              // when refused: 503 or 429
  };
  Grant Take(const std::string& client);

 private:
  void Give(const std::string& client);

  const int total_, per_client_;
  std::mutex mu_;
  int open_ = 0;
  std::map<std::string, int> by_client_;
};

}  // namespace wavebake::web
