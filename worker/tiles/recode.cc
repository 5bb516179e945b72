#include "worker/tiles/recode.h"

#include <mutex>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_params_io.h"
#include "core/util/parallel_for.h"
#include "storage/store/params_json.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_group.h"
#include "worker/columns/finalize.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

absl::Status CheckTrace(const BakeContext& ctx, const std::filesystem::path& traced) {
  const std::filesystem::path staging = store::Path(traced, store::kStaging);
  if (!std::filesystem::is_directory(staging))
    return absl::FailedPreconditionError(
        absl::StrCat("traced: ", traced.string(), " has no staging (bake it with keep_staging)"));
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(staging);
  if (!attrs.ok()) return attrs.status();
  if (!attrs->contains("trace"))
    return absl::FailedPreconditionError(
        absl::StrCat(staging.string(), ": no trace record (not a kept staging)"));
  const nlohmann::json& have = (*attrs)["trace"];
  const nlohmann::json want = TraceRecord(ctx);
  // The scene first: another scene differs in everything that follows.
  std::vector<std::string> fields = {"scene_hash"};
  for (const auto& [field, value] : want.items())
    if (field != "scene_hash") fields.push_back(field);
  for (const std::string& field : fields) {
    const nlohmann::json& value = want[field];
    if (!have.contains(field) || have[field] != value)
      return absl::FailedPreconditionError(
          absl::StrCat("traced: ", field, " is ", have.value(field, nlohmann::json()).dump(),
                       " in ", traced.string(), ", the new parameters need ", value.dump()));
  }
  return absl::OkStatus();
}

// The new store's staging/ shares the trace's arrays through symbolic links
// (nothing is copied; FINALIZE drops the links, not their targets) and holds
// its own group results.
absl::Status LinkStaging(const std::filesystem::path& traced, const std::filesystem::path& out) {
  if (absl::Status s = WriteGroup(out); !s.ok()) return s;
  if (absl::Status s = WriteGroup(store::Path(out, store::kStaging)); !s.ok()) return s;
  for (const char* name : {store::kStagingTransport, store::kStagingTileEnergy}) {
    std::error_code ec;
    std::filesystem::create_directory_symlink(std::filesystem::absolute(store::Path(traced, name)),
                                              store::Path(out, name), ec);
    if (ec) return absl::InternalError(absl::StrCat(out.string(), ": ", name, ": ", ec.message()));
  }
  return absl::OkStatus();
}

std::filesystem::path PartialBeside(const std::filesystem::path& out, const char* what) {
  return out.parent_path() / absl::StrCat(".", out.filename().string(), ".", what);
}

}  // namespace

nlohmann::json TraceRecord(const BakeContext& ctx) {
  nlohmann::json j = ToJson(ctx.params, params::Stage::kTrace);
  j["scene_hash"] = ctx.scene_hash;
  j["ray_epsilon"] = ctx.epsilon;  // the offset the rows were traced with
  return j;
}

absl::StatusOr<uint64_t> TraceStaging(const BakeContext& ctx, const std::filesystem::path& dir,
                                      const TraceOptions& options) {
  if (std::filesystem::exists(dir))
    return absl::AlreadyExistsError(absl::StrCat("dir: ", dir.string(), " exists"));
  const std::filesystem::path partial = PartialBeside(dir, "tracing");
  std::error_code ec;
  std::filesystem::remove_all(partial, ec);
  uint64_t rays = 0;  // guarded by progress
  int tiles = 0;      // guarded by progress
  std::mutex progress;
  absl::Status s = CreateStaging(ctx.plan, partial, TraceRecord(ctx));
  if (s.ok()) {
    s = ParallelTasks(ctx.plan.all_tiles(), options.threads, [&](int t) {
      TileStats stats;
      if (absl::Status b = BakeTile(ctx, partial, t, &stats, {.cancel = options.cancel}); !b.ok())
        return b;
      // Counted under the lock so that on_tile sees the counts in order.
      std::lock_guard lock(progress);
      rays += stats.rays_traced;
      ++tiles;
      if (options.on_tile) options.on_tile(tiles, rays);
      return absl::OkStatus();
    });
  }
  if (s.ok()) {
    std::filesystem::rename(partial, dir, ec);
    if (ec) s = absl::InternalError(absl::StrCat("dir: ", dir.string(), ": ", ec.message()));
  }
  if (!s.ok()) {
    std::filesystem::remove_all(partial, ec);
    return s;
  }
  return rays;
}

absl::Status Recode(const BakeContext& ctx, const std::filesystem::path& traced,
                    const std::filesystem::path& out, const RecodeOptions& options) {
  if (std::filesystem::exists(out))
    return absl::AlreadyExistsError(absl::StrCat("out: ", out.string(), " exists"));
  if (absl::Status s = CheckTrace(ctx, traced); !s.ok()) return s;
  const std::filesystem::path partial = PartialBeside(out, "recoding");
  std::error_code ec;
  std::filesystem::remove_all(partial, ec);
  absl::Status s = LinkStaging(traced, partial);
  if (s.ok()) {
    s = ParallelTasks(ctx.plan.groups, options.threads,
                      [&](int g) { return TransformColumns(ctx, partial, g, nullptr); });
  }
  if (s.ok()) s = Finalize(ctx, partial, {.keep_staging = false});
  if (s.ok()) {
    std::filesystem::rename(partial, out, ec);
    if (ec) s = absl::InternalError(absl::StrCat("out: ", out.string(), ": ", ec.message()));
  }
  if (!s.ok()) std::filesystem::remove_all(partial, ec);
  return s;
}

}  // namespace wavebake
