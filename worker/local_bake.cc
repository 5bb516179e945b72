#include "worker/local_bake.h"

#include <unistd.h>

#include <chrono>
#include <mutex>
#include <thread>

#include "absl/strings/str_cat.h"
#include "storage/scoped_dir.h"
#include "storage/store_reader.h"
#include "worker/bake_context.h"
#include "worker/bake_tile.h"
#include "worker/finalize.h"
#include "worker/publish_store.h"
#include "worker/staging.h"
#include "worker/task_pool.h"
#include "worker/transform_columns.h"

namespace wavebake {
namespace {

// Progress and counters shared by the pool threads; callbacks serialized.
class Progress {
 public:
  explicit Progress(const LocalBakeOptions& options) : callback_(options.progress) {}
  void StartPhase(const char* phase, int64_t total) {
    std::lock_guard<std::mutex> lock(mu_);
    state_.phase = phase;
    state_.done = 0;
    state_.total = total;
    Report();
  }
  void TaskDone(uint64_t rays) {
    std::lock_guard<std::mutex> lock(mu_);
    ++state_.done;
    state_.rays += rays;
    Report();
  }
  uint64_t rays() const { return state_.rays; }

 private:
  void Report() {
    if (callback_) callback_(state_);
  }
  std::function<void(const BakeProgress&)> callback_;
  std::mutex mu_;
  BakeProgress state_;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

absl::Status BakeAllTiles(const BakeContext& ctx, const std::filesystem::path& store, int threads,
                          Progress& progress, BakeSummary* summary) {
  std::mutex mu;
  progress.StartPhase("bake tiles", ctx.plan.tiles());
  return RunTasks(ctx.plan.tiles(), threads, [&](int tile) -> absl::Status {
    TileStats stats;
    if (absl::Status s = BakeTile(ctx, store, tile, &stats); !s.ok()) return s;
    {
      std::lock_guard<std::mutex> lock(mu);
      summary->samples += stats.samples;
      summary->staging_bytes += stats.bytes_written;
    }
    progress.TaskDone(stats.rays_traced);
    return absl::OkStatus();
  });
}

absl::Status TransformAllGroups(const BakeContext& ctx, const std::filesystem::path& store,
                                int threads, Progress& progress) {
  progress.StartPhase("transform columns", ctx.plan.groups);
  return RunTasks(ctx.plan.groups, threads, [&](int group) -> absl::Status {
    if (absl::Status s = TransformColumns(ctx, store, group, nullptr); !s.ok()) return s;
    progress.TaskDone(0);
    return absl::OkStatus();
  });
}

// The store's own account of itself (worker/store_manifest.h).
absl::Status ReadManifestSummary(const std::filesystem::path& store, BakeSummary* summary) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  const nlohmann::json& stats = info->attrs["stats"];
  summary->bits = info->bits;
  summary->nnz = stats["nnz"].get<int64_t>();
  summary->transport_bytes = stats["bytes"]["transport"].get<uint64_t>();
  summary->raw_bytes = stats["bytes"]["raw_float32"].get<uint64_t>();
  summary->column_error_mean = stats["column_error"]["mean"].get<double>();
  summary->column_error_max = stats["column_error"]["max"].get<double>();
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<BakeSummary> RunLocalBake(std::string_view scene_spec, const BakeParams& params,
                                         const std::filesystem::path& out_arg,
                                         const LocalBakeOptions& options) {
  // "x.wbk/" names x.wbk: the partial store must sit beside it, not inside.
  const std::filesystem::path out = out_arg.has_filename() ? out_arg : out_arg.parent_path();
  // Everything that can be refused is refused before a directory exists.
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext(scene_spec, params);
  if (!ctx.ok()) return ctx.status();
  if (absl::Status s = CheckOutputPath(out); !s.ok()) return s;
  const int threads = options.threads > 0
                          ? options.threads
                          : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  // Removed unless the bake got as far as publishing it (by rename).
  ScopedDir partial(out.string() + absl::StrCat(".partial-", ::getpid()));
  std::error_code ec;
  std::filesystem::remove_all(partial.path(), ec);  // a stale one of a crashed namesake
  const JobPlan& plan = (*ctx)->plan;
  if (absl::Status s = CreateStaging(plan, partial.path()); !s.ok()) return s;

  BakeSummary summary;
  summary.tiles = plan.tiles();
  summary.groups = plan.groups;
  Progress progress(options);
  auto start = std::chrono::steady_clock::now();
  if (absl::Status s = BakeAllTiles(**ctx, partial.path(), threads, progress, &summary); !s.ok())
    return s;
  summary.seconds_bake = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  if (absl::Status s = TransformAllGroups(**ctx, partial.path(), threads, progress); !s.ok())
    return s;
  summary.seconds_columns = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  progress.StartPhase("finalize", 1);
  if (absl::Status s = Finalize(**ctx, partial.path(),
                                {.keep_staging = options.keep_staging || params.keep_staging});
      !s.ok()) {
    return s;
  }
  progress.TaskDone(0);
  summary.seconds_finalize = SecondsSince(start);
  summary.rays_traced = progress.rays();

  if (absl::Status s = ReadManifestSummary(partial.path(), &summary); !s.ok()) return s;
  if (absl::Status s = PublishStore(partial.path(), out); !s.ok()) return s;
  return summary;
}

}  // namespace wavebake
