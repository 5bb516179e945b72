#pragma once
// What a FINALIZE shard needs of the matrix-wide scan and step choice
// (worker/columns/finalize_parts.h): where each group's elements start, each
// column's step and the codes' clamp. Every shard needs all of it, and
// working it out reads every group's column table and runs the O(M) step
// search: with 64 shards at N = 128 (M = 98 304), FINALIZE took 3.9–4.5 s of
// CPU on the refined bunny, 2.6–2.9 s once shared. So the first shard to work it out keeps it in
// staging/finalize/plan.wbp, and the others read M floats instead. A group
// result written anew removes the file (WriteGroupResult): the plan is a
// function of the group results and of the column parameters, and a store's
// column parameters change only with all its group results (a recode).
#include <cstdint>
#include <filesystem>
#include <vector>

#include "absl/status/statusor.h"
#include "core/bake/job_plan.h"

namespace wavebake {

struct ShardPlan {
  std::vector<int64_t> group_offsets;  // [groups + 1], the last is nnz
  std::vector<float> steps;            // Δ_c per column
  int max_code = 0;
  int64_t nnz() const { return group_offsets.back(); }
};

std::filesystem::path ShardPlanPath(const std::filesystem::path& store);
// Written atomically; shards that write it at once write the same bytes.
absl::Status WriteShardPlan(const std::filesystem::path& store, const ShardPlan& plan);
// NotFound if no shard has written it; DataLoss naming the file if it is not
// a plan of `job`'s groups and columns.
absl::StatusOr<ShardPlan> ReadShardPlan(const std::filesystem::path& store, const JobPlan& job);
absl::Status RemoveShardPlan(const std::filesystem::path& store);

}  // namespace wavebake
