#pragma once
// How FINALIZE is cut into tasks (DESIGN.md §2): FinalizeShards(groups)
// shard tasks, then one last task. Shard k owns groups [ShardFirstGroup(k),
// ShardFirstGroup(k + 1)): it writes the chunks of transport/indices and
// transport/data whose first element lies in them, and records its columns'
// quantization outcome; the last task writes indptr, depth, scale, samples
// and the manifest. Pure arithmetic shared by the coordinator (to plan) and
// the workers (to run).
//
// Every shard needs what every group's column table gives (the step choice
// is matrix-wide, core/columns/quantization_steps.h); the first to read them
// all keeps the result for the others (worker/columns/shard_plan.h), but
// shards that start together each read them, so the count is bounded: with
// more than 64 shards those reads (shards × M table entries) would outgrow
// what a shard writes on the largest stores (docs/SCALING.md).
#include <cstdint>

namespace wavebake {

inline constexpr int kMaxFinalizeShards = 64;

inline int FinalizeShards(int groups) {
  return groups < 1 ? 1 : groups < kMaxFinalizeShards ? groups : kMaxFinalizeShards;
}

// Shards and the last task.
inline int FinalizeTasks(int groups) { return FinalizeShards(groups) + 1; }

// First group of shard `shard` (shard = FinalizeShards(groups): `groups`).
inline int ShardFirstGroup(int groups, int shard) {
  return static_cast<int>(int64_t{groups} * shard / FinalizeShards(groups));
}

}  // namespace wavebake
