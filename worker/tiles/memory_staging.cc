#include "worker/tiles/memory_staging.h"

#include <sys/mman.h>

#include <numeric>
#include <utility>

namespace wavebake {
namespace {

constexpr size_t kPage = size_t{4} << 10;

uint64_t StagingBytes(const JobPlan& plan) {
  return uint64_t(plan.groups) * plan.all_tiles() * plan.group_size * plan.tile_cells() *
         sizeof(float);
}

}  // namespace

std::shared_ptr<MemoryStaging::Job> MemoryStaging::Job::Map(const JobPlan& plan) {
  const size_t bytes = (StagingBytes(plan) + kPage - 1) / kPage * kPage;
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return nullptr;
  // No MADV_HUGEPAGE: with the kernel's usual defrag=madvise, a fault in
  // such a region may compact memory first. Touching 400 MB took 0.04 s or
  // 0.66–1.0 s with it (free huge pages or not), 0.17 s steadily without.
  return std::make_shared<Job>(plan, Mapping{static_cast<float*>(p), bytes});
}

MemoryStaging::Job::Job(const JobPlan& plan, Mapping mapping)
    : tiles_(plan.all_tiles()),
      slots_(size_t(plan.groups) * plan.all_tiles()),
      chunk_floats_(size_t(plan.group_size) * plan.tile_cells()),
      mapping_(mapping),
      state_(slots_, State::kEmpty),
      groups_(plan.groups),
      group_bytes_(plan.groups, 0) {}

MemoryStaging::Job::~Job() { ::munmap(mapping_.data, mapping_.bytes); }

std::span<float> MemoryStaging::Job::BeginWrite(int g, int t) {
  std::lock_guard lock(mu_);
  State& s = state_[Slot(g, t)];
  if (s != State::kEmpty) return {};
  s = State::kWriting;
  return {mapping_.data + Slot(g, t) * chunk_floats_, chunk_floats_};
}

void MemoryStaging::Job::Publish(int g, int t) {
  std::lock_guard lock(mu_);
  state_[Slot(g, t)] = State::kPublished;
}

void MemoryStaging::Job::Abandon(int g, int t) {
  std::lock_guard lock(mu_);
  state_[Slot(g, t)] = State::kEmpty;
}

std::span<const float> MemoryStaging::Job::Chunk(int g, int t) const {
  std::lock_guard lock(mu_);
  if (state_[Slot(g, t)] != State::kPublished) return {};
  return {mapping_.data + Slot(g, t) * chunk_floats_, chunk_floats_};
}

void MemoryStaging::Job::SetGroup(int g, std::shared_ptr<const GroupResult> result,
                                  uint64_t bytes) {
  std::lock_guard lock(mu_);
  groups_[g] = std::move(result);
  group_bytes_[g] = bytes;
}

uint64_t MemoryStaging::Job::GroupBytes(int g) const {
  std::lock_guard lock(mu_);
  return group_bytes_[g];
}

uint64_t MemoryStaging::Job::group_bytes() const {
  std::lock_guard lock(mu_);
  return std::accumulate(group_bytes_.begin(), group_bytes_.end(), uint64_t{0});
}

std::shared_ptr<const GroupResult> MemoryStaging::Job::Group(int g) const {
  std::lock_guard lock(mu_);
  return groups_[g];
}

std::shared_ptr<MemoryStaging::Job> MemoryStaging::Admit(const std::filesystem::path& store,
                                                         const JobPlan& plan) {
  std::lock_guard lock(mu_);
  const std::string key = store.lexically_normal().string();
  if (auto it = jobs_.find(key); it != jobs_.end()) return it->second;
  if (refused_.count(key)) return nullptr;
  const uint64_t bytes = StagingBytes(plan);
  std::shared_ptr<Job> job = held_ + bytes <= budget_ ? Job::Map(plan) : nullptr;
  if (job == nullptr) {
    refused_[key] = true;
    return nullptr;
  }
  held_ += job->bytes();
  jobs_[key] = job;
  return job;
}

std::shared_ptr<MemoryStaging::Job> MemoryStaging::Find(const std::filesystem::path& store) const {
  std::lock_guard lock(mu_);
  auto it = jobs_.find(store.lexically_normal().string());
  return it == jobs_.end() ? nullptr : it->second;
}

bool MemoryStaging::HoldGroup(const std::filesystem::path& store, int g,
                              std::shared_ptr<const GroupResult> result, uint64_t bytes) {
  std::lock_guard lock(mu_);
  auto it = jobs_.find(store.lexically_normal().string());
  if (it == jobs_.end()) return false;
  const uint64_t others = held_ - it->second->GroupBytes(g);
  if (others + bytes > budget_) return false;
  it->second->SetGroup(g, std::move(result), bytes);
  held_ = others + bytes;
  return true;
}

void MemoryStaging::Drop(const std::filesystem::path& store) {
  std::lock_guard lock(mu_);
  const std::string key = store.lexically_normal().string();
  if (auto it = jobs_.find(key); it != jobs_.end()) {
    held_ -= it->second->bytes() + it->second->group_bytes();
    jobs_.erase(it);
  }
  refused_.erase(key);
}

uint64_t MemoryStaging::held_bytes() const {
  std::lock_guard lock(mu_);
  return held_;
}

}  // namespace wavebake
