#include "web/job_source.h"

#include <mutex>

namespace wavebake::web {

void SourceSlot::Set(std::shared_ptr<JobSource> source) {
  std::shared_ptr<JobSource> previous;
  {
    std::unique_lock lock(mu_);  // waits for every Use of the previous source
    previous = std::exchange(source_, std::move(source));
  }
}

SourceSlot::Use SourceSlot::Get() const {
  std::shared_lock lock(mu_);
  std::shared_ptr<JobSource> source = source_;
  return Use(std::move(lock), std::move(source));
}

}  // namespace wavebake::web
