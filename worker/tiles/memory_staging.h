#pragma once
// The blocked transpose without the store's round trip (DESIGN.md §2): when
// every task of a job runs in one process (the embedded bake) and the job's
// staging fits a stated memory budget, BAKE_TILE leaves its staging chunks
// here, raw float32, and TRANSFORM_COLUMNS reads them from here, instead of
// both compressing, writing, reading and decompressing every chunk of
// staging/transport (on the bunny at N = 64: 402 MB of rows through zstd and
// the page cache, a fifth of a refined bake's CPU). Everything else of
// staging (the arrays' metadata, staging/tile_energy, the group results)
// stays in the store, so a job whose staging does not fit, a kept staging
// (--keep-staging, recodes) and remote workers use the chunked store as
// before, and a store's bytes do not depend on where its staging was.
//
// A chunk is written once: a retried tile finds its chunks there (the same
// values: they depend only on the context and the tile) and skips them.
// Memory: at most `budget_bytes` of chunks and group results over all jobs
// held, the chunks in one mapping per job.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "core/bake/job_plan.h"

namespace wavebake {

// What TRANSFORM_COLUMNS leaves for FINALIZE (worker/columns/group_result.h);
// held here, never looked into.
struct GroupResult;

class MemoryStaging {
 public:
  // What one job holds: chunk (g, t) of staging/transport at slot
  // g·all_tiles + t, and for t ≥ tiles chunk (g, t − tiles) of
  // staging/aux_transport (a camera's auxiliary rows, core/bake/bake_gather.h).
  class Job;

  explicit MemoryStaging(uint64_t budget_bytes) : budget_(budget_bytes) {}

  // The job staged at `store` (its partial store directory), admitted on the
  // first call if its whole staging fits what is left of the budget; null
  // if it does not (then it is never admitted later: every tile of a job
  // goes the same way, unless memory for it cannot be mapped).
  std::shared_ptr<Job> Admit(const std::filesystem::path& store, const JobPlan& plan);
  // The job if it was admitted, else null.
  std::shared_ptr<Job> Find(const std::filesystem::path& store) const;
  // Forgets the job (FINALIZE drops staging); its memory goes when the last
  // task still reading it lets go.
  void Drop(const std::filesystem::path& store);

  // TRANSFORM_COLUMNS' result for group g of the job at `store`
  // (worker/columns/group_result.h, `bytes` long), held for FINALIZE
  // instead of staging/groups/<g>.wbg: on the bunny at N = 64, 66 MB of
  // results whose zstd, files and reads cost 5 % of the bake's CPU. False,
  // holding nothing, if the job is not held or the result does not fit what
  // is left of the budget: the caller writes the file then. A group held
  // again (a retry: the same values) replaces the one before.
  bool HoldGroup(const std::filesystem::path& store, int g,
                 std::shared_ptr<const GroupResult> result, uint64_t bytes);

  uint64_t held_bytes() const;

 private:
  mutable std::mutex mu_;
  uint64_t budget_;
  uint64_t held_ = 0;
  std::map<std::string, std::shared_ptr<Job>> jobs_;
  std::map<std::string, bool> refused_;  // jobs that did not fit
};

class MemoryStaging::Job {
 public:
  // One anonymous mapping for the job's chunks; null if it cannot be mapped.
  static std::shared_ptr<Job> Map(const JobPlan& plan);
  struct Mapping {
    float* data = nullptr;
    size_t bytes = 0;
  };
  Job(const JobPlan& plan, Mapping mapping);
  ~Job();
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  // Chunk (g, t) to write if nobody wrote or is writing it, else empty
  // (a retried or duplicated tile: the chunk is, or will be, the same).
  // Publish (or Abandon, if the write failed) after filling it.
  std::span<float> BeginWrite(int g, int t);
  void Publish(int g, int t);
  void Abandon(int g, int t);
  // Chunk (g, t) once published, else empty. Never written again.
  std::span<const float> Chunk(int g, int t) const;

  // Group g's result held for FINALIZE (MemoryStaging::HoldGroup), or null.
  std::shared_ptr<const GroupResult> Group(int g) const;

  uint64_t bytes() const { return slots_ * chunk_floats_ * sizeof(float); }
  uint64_t group_bytes() const;

 private:
  enum class State : uint8_t { kEmpty, kWriting, kPublished };
  size_t Slot(int g, int t) const { return size_t(g) * tiles_ + t; }  // tiles_: all_tiles()

  mutable std::mutex mu_;
  int tiles_;
  size_t slots_, chunk_floats_;
  Mapping mapping_;
  std::vector<State> state_;
  friend class MemoryStaging;
  // Holds `result` (`bytes` long) as group g's, in place of any before it.
  void SetGroup(int g, std::shared_ptr<const GroupResult> result, uint64_t bytes);
  uint64_t GroupBytes(int g) const;

  std::vector<std::shared_ptr<const GroupResult>> groups_;  // [groups]
  std::vector<uint64_t> group_bytes_;
};

}  // namespace wavebake
