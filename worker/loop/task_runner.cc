#include "worker/loop/task_runner.h"

#include <stdio.h>

#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "core/bake/finalize_shards.h"
#include "proto/bake_request.h"
#include "storage/store/store_reader.h"
#include "worker/columns/finalize.h"
#include "worker/columns/local_columns.h"
#include "worker/columns/store_manifest.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/recode.h"
#include "worker/tiles/row_reuse.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

absl::Status Cancelled(const v1::Task& task) {
  return absl::CancelledError(absl::StrCat("job ", task.job_id(), ": ",
                                           v1::TaskKind_Name(task.kind()), " ", task.index(),
                                           " stopped: its lease was cancelled"));
}

// An update's old store: a relative update_from is under the store root, as
// job stores are (a coordinator's job, whose scene comes as update_scene);
// an absolute one is the embedded bake's, whose store names its scene.
absl::StatusOr<OldStore> UpdateSource(const v1::BakeRequest& request, const TaskEnv& env) {
  const std::filesystem::path from(request.update_from());
  OldStore old;
  old.path = from.is_absolute() ? from : env.store_root / from;
  old.recorded = request.update_from();
  if (request.has_update_scene()) {
    absl::StatusOr<SceneSpec> scene = env.scenes->Resolve(request.update_scene(), env.fetch);
    if (!scene.ok()) return scene.status();
    old.scene = scene->load;
    old.scene_files = scene->files;
  }
  return old;
}

// The job's context, built once per worker (worker/loop/context_cache.h). The
// store records the scene as every worker would name it, not by where this
// worker found it.
absl::StatusOr<ContextCache::Context> JobContext(const v1::Task& task, const TaskEnv& env) {
  const std::string key = absl::StrCat(task.job_id(), "\n", task.request().SerializeAsString());
  return env.contexts->Get(key, [&]() -> absl::StatusOr<std::unique_ptr<BakeContext>> {
    absl::StatusOr<BakeParams> params = ToBakeParams(task.request());
    if (!params.ok()) return params.status();
    absl::StatusOr<SceneSpec> scene = env.scenes->Resolve(task.request().scene(), env.fetch);
    if (!scene.ok()) return scene.status();
    absl::StatusOr<std::unique_ptr<BakeContext>> ctx =
        MakeBakeContext(scene->load, *params, scene->files.get());
    if (!ctx.ok()) return ctx;
    (*ctx)->scene_spec = scene->recorded;
    if (!params->update_from.empty()) {
      absl::StatusOr<OldStore> old = UpdateSource(task.request(), env);
      if (!old.ok()) return old.status();
      absl::StatusOr<std::shared_ptr<const RowReuse>> reuse =
          PlanRowReuse(**ctx, *old, params->update_exact);
      if (!reuse.ok()) return reuse.status();
      (*ctx)->reuse = *std::move(reuse);
    }
    return ctx;
  });
}

// Both sides cut the job with core/bake/job_plan.h; a mismatch means they disagree
// about the scene or the parameters, and nothing this worker writes would fit.
absl::Status CheckPlan(const v1::Task& task, const JobPlan& plan) {
  if (task.tiles() == plan.all_tiles() && task.groups() == plan.groups) return absl::OkStatus();
  return absl::FailedPreconditionError(
      absl::StrCat("plan: the coordinator planned ", task.tiles(), " tiles and ", task.groups(),
                   " groups, this worker ", plan.all_tiles(), " and ", plan.groups));
}

// Tasks run only in a partial directory the planner reserved (see
// kPartialMarker): never in one a cancelled job's cleanup removed.
absl::Status CheckPartial(const std::filesystem::path& partial) {
  std::error_code ec;
  if (std::filesystem::exists(partial / kPartialMarker, ec)) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat(
      "store: ", partial.string(), " is not a reserved partial store (the job ended)"));
}

absl::StatusOr<TaskOutcome> BakeTileTask(const v1::Task& task, const BakeContext& ctx,
                                         const std::filesystem::path& partial,
                                         TaskProgress& progress, MemoryStaging* memory) {
  if (absl::Status s = CreateStaging(ctx.plan, partial, TraceRecord(ctx)); !s.ok()) return s;
  TileStats stats;
  absl::Status s = BakeTile(ctx, partial, task.index(), &stats,
                            {&progress.cancel, &progress.rays_traced}, memory);
  if (!s.ok()) return s;
  nlohmann::json tile_stats = {{"samples", stats.samples}};
  if (ctx.reuse) tile_stats["rows_reused"] = stats.rows_reused;
  return TaskOutcome{.rays_traced = static_cast<int64_t>(stats.rays_traced),
                     .bytes_written = static_cast<int64_t>(stats.bytes_written),
                     .stats_json = tile_stats.dump()};
}

// Cancel is seen between staging chunks and columns: a large group at a
// large N takes as long as a tile.
absl::StatusOr<TaskOutcome> TransformTask(const v1::Task& task, const BakeContext& ctx,
                                          const std::filesystem::path& partial,
                                          TaskProgress& progress, MemoryStaging* memory) {
  GroupStats stats;
  // An update (worker/tiles/row_reuse.h) stages through the store, never in memory.
  absl::Status s =
      StartsFromOldCodings(ctx)
          ? LocalTransformColumns(ctx, partial, task.index(), &stats, {&progress.cancel})
          : TransformColumns(ctx, partial, task.index(), &stats, {&progress.cancel}, memory);
  if (!s.ok()) return s;
  return TaskOutcome{.rays_traced = 0,
                     .bytes_written = static_cast<int64_t>(stats.bytes_written),
                     .stats_json = nlohmann::json{{"columns", stats.columns},
                                                  {"kept", stats.kept},
                                                  {"min_bits", stats.min_bits}}
                                       .dump()};
}

// A FINALIZE shard (core/bake/finalize_shards.h): its chunks of the CSC arrays.
// A retry after the job's store was published finds nothing to do.
absl::StatusOr<TaskOutcome> FinalizeShardTask(const v1::Task& task, const BakeContext& ctx,
                                              const std::filesystem::path& partial,
                                              const std::filesystem::path& out, int threads,
                                              TaskProgress& progress, MemoryStaging* memory) {
  std::error_code ec;
  if (!std::filesystem::exists(partial, ec) && ReadStoreInfo(out).ok()) return TaskOutcome{};
  if (absl::Status s = CheckPartial(partial); !s.ok()) return s;
  if (absl::Status s = FinalizeShard(ctx, partial, task.index(),
                                     {.keep_staging = ctx.params.keep_staging,
                                      .cancel = &progress.cancel,
                                      .threads = threads,
                                      .memory = memory});
      !s.ok())
    return s;
  return TaskOutcome{};
}

// FINALIZE's last task: the column arrays and the manifest, then the store
// appears at its path by one rename.
absl::StatusOr<TaskOutcome> FinalizeTask(const v1::Task& task, const BakeContext& ctx,
                                         const std::filesystem::path& partial,
                                         const std::filesystem::path& out, int threads,
                                         TaskProgress& progress, MemoryStaging* memory) {
  std::error_code ec;
  const bool retry_after_publish = !std::filesystem::exists(partial, ec) && ReadStoreInfo(out).ok();
  if (!retry_after_publish) {
    if (absl::Status s = CheckPartial(partial); !s.ok()) return s;
    // Before FINALIZE drops staging/groups.
    RecodedColumns recomputed{ctx.plan.columns, ctx.plan.columns};
    if (StartsFromOldCodings(ctx)) {
      absl::StatusOr<RecodedColumns> n = RecomputedColumns(ctx.plan, partial);
      if (!n.ok()) return n.status();
      recomputed = *n;
    }
    if (absl::Status s = FinalizeStore(ctx, partial,
                                       {.keep_staging = ctx.params.keep_staging,
                                        .cancel = &progress.cancel,
                                        .threads = threads,
                                        .memory = memory});
        !s.ok())
      return s;
    if (ctx.reuse) {
      if (absl::Status s =
              WriteUpdateRecord(partial, *ctx.reuse, recomputed.recomputed, recomputed.searched,
                                ctx.plan.columns, ctx.plan.bounces);
          !s.ok())
        return s;
    }
    if (progress.cancel.load()) return Cancelled(task);
    if (absl::Status s = PublishFinishedStore(partial, out); !s.ok()) return s;
  }
  std::filesystem::remove(out / kPartialMarker, ec);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(out);
  if (!info.ok()) return info.status();
  return TaskOutcome{
      .rays_traced = 0,
      .bytes_written = static_cast<int64_t>(retry_after_publish ? 0 : DirectoryBytes(out)),
      .stats_json = info->attrs.value("stats", nlohmann::json::object()).dump()};
}

}  // namespace

absl::StatusOr<TaskOutcome> RunTask(const v1::Task& task, const TaskEnv& env,
                                    TaskProgress& progress) {
  absl::StatusOr<ContextCache::Context> ctx = JobContext(task, env);
  if (!ctx.ok()) return ctx.status();
  if (absl::Status s = CheckPlan(task, (*ctx)->plan); !s.ok()) return s;
  const std::filesystem::path out = env.store_root / task.store_path();
  const std::filesystem::path partial = env.store_root / PartialStorePath(task.store_path());
  if (progress.cancel.load()) return Cancelled(task);

  absl::StatusOr<TaskOutcome> outcome;
  switch (task.kind()) {
    case v1::BAKE_TILE:
      if (absl::Status s = CheckPartial(partial); !s.ok()) return s;
      outcome = BakeTileTask(task, **ctx, partial, progress, env.memory_staging);
      break;
    case v1::TRANSFORM_COLUMNS:
      if (absl::Status s = CheckPartial(partial); !s.ok()) return s;
      outcome = TransformTask(task, **ctx, partial, progress, env.memory_staging);
      break;
    case v1::FINALIZE:
      outcome =
          task.index() < FinalizeShards(task.groups())
              ? FinalizeShardTask(task, **ctx, partial, out, env.threads, progress,
                                  env.memory_staging)
              : FinalizeTask(task, **ctx, partial, out, env.threads, progress, env.memory_staging);
      break;
    default:
      return absl::InvalidArgumentError(
          absl::StrCat("kind: ", static_cast<int>(task.kind()), " is not a task kind"));
  }
  if (progress.cancel.load()) {
    // A cancelled job's cleanup may have run while this task still wrote:
    // what it recreated carries no marker and goes (kPartialMarker).
    std::error_code ec;
    if (!std::filesystem::exists(partial / kPartialMarker, ec))
      std::filesystem::remove_all(partial, ec);
    return Cancelled(task);
  }
  if (outcome.ok()) {
    progress.rays_traced = static_cast<uint64_t>(outcome->rays_traced);
    progress.bytes_written = static_cast<uint64_t>(outcome->bytes_written);
  }
  return outcome;
}

absl::Status PublishFinishedStore(const std::filesystem::path& partial,
                                  const std::filesystem::path& out) {
  if (::rename(partial.c_str(), out.c_str()) == 0) return absl::OkStatus();
  const int err = errno;
  if (ReadStoreInfo(out).ok()) {  // another FINALIZE of the job published it first
    std::error_code ec;
    std::filesystem::remove_all(partial, ec);
    return absl::OkStatus();
  }
  return absl::InternalError(
      absl::StrCat("rename ", partial.string(), " -> ", out.string(), ": ", std::strerror(err)));
}

}  // namespace wavebake
