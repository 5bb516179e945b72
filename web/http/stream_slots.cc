#include "web/http/stream_slots.h"

namespace wavebake::web {

StreamSlots::Grant StreamSlots::Take(const std::string& client) {
  std::lock_guard lock(mu_);
  if (open_ >= total_) return {nullptr, 503};
  int& mine = by_client_[client];
  if (mine >= per_client_) return {nullptr, 429};
  ++mine;
  ++open_;
  // The slot goes back when the last copy of the grant goes (non-null, so
  // that a grant tests true; the deleter frees nothing).
  return {std::shared_ptr<void>(this, [this, client](void*) { Give(client); }), 0};
}

void StreamSlots::Give(const std::string& client) {
  std::lock_guard lock(mu_);
  --open_;
  if (auto it = by_client_.find(client); it != by_client_.end() && --it->second == 0)
    by_client_.erase(it);
}

}  // namespace wavebake::web
