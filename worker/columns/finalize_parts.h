#pragma once
// The pieces FINALIZE's tasks share (worker/columns/finalize.h): the scan of every
// group's column table, the matrix-wide step choice, one group quantized,
// the CSC arrays' specs, and the file in which a shard hands its columns'
// quantization outcome to the last task. Internal to worker/finalize*.cc.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/columns/quantization_steps.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/finalize.h"
#include "worker/columns/group_result.h"
#include "worker/columns/shard_plan.h"
#include "worker/tiles/bake_context.h"

namespace wavebake {

// Every column's table entry in matrix order, and where each group's
// elements start in transport/indices and data (group_offsets[groups] = nnz).
// A missing group is FailedPrecondition: FINALIZE ran too early.
struct FinalizeScan {
  int64_t nnz = 0;
  std::vector<GroupColumn> columns;
  std::vector<int64_t> group_offsets;
};
absl::StatusOr<FinalizeScan> ScanGroups(const JobPlan& plan, const std::filesystem::path& store,
                                        const FinalizeOptions& options);

// The steps of every column (core/columns/quantization_steps.h), from the scan alone.
StepPlan PlanFinalizeSteps(const FinalizeScan& scan, const BakeParams& params);
// What the shards take of them (worker/columns/shard_plan.h).
ShardPlan MakeShardPlan(const FinalizeScan& scan, const StepPlan& steps);

// Threads of a FINALIZE task: options.threads, or one per hardware thread.
int FinalizeThreads(const FinalizeOptions& options);

// A group's columns quantized (DESIGN.md §1 "Scaling and quantization"):
// the codes, and per column its achieved quantization error energy
// (weighted like the selection) and the bits its largest code needs (0 for
// a column without codes).
struct QuantizedGroup {
  std::shared_ptr<const GroupResult> result;
  DefaultInitVector<int16_t> q;  // parallel to result.positions, written in full
  std::vector<double> error_energy;
  std::vector<int> bits;
};
absl::StatusOr<QuantizedGroup> QuantizeGroup(const BakeContext& ctx, const ShardPlan& steps,
                                             const std::filesystem::path& store,
                                             const FinalizeOptions& options, int g);

struct CscArrays {
  ZarrArray indptr, indices, data, depth, scale;
};
// Creates transport/ and its arrays, or opens them if they exist with the
// same spec (every shard and the last task call it).
absl::StatusOr<CscArrays> CreateTransport(const std::filesystem::path& store, int columns,
                                          int64_t nnz);

// A shard's columns [first_column, first_column + count): the quantization
// error energy and bits of each, written atomically under staging/ when the
// shard has written its chunks (its presence says the shard is done).
std::filesystem::path ShardOutcomePath(const std::filesystem::path& store, int shard);
absl::Status WriteShardOutcome(const std::filesystem::path& store, int shard, int first_column,
                               std::span<const double> error_energy, std::span<const int> bits);
// Fills error_energy/bits[first_column, +count); FailedPrecondition if the
// shard has not finished.
absl::Status ReadShardOutcome(const std::filesystem::path& store, int shard, int first_column,
                              int count, std::span<double> error_energy, std::span<int> bits);

}  // namespace wavebake
