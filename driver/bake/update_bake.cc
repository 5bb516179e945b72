#include "driver/bake/update_bake.h"

#include <chrono>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "storage/files/scoped_dir.h"
#include "storage/scene_files/scene_loader.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "storage/store/store_scene.h"
#include "storage/zarr/zarr_group.h"
#include "worker/columns/publish_store.h"
#include "worker/tiles/row_reuse.h"

namespace wavebake::driver {

absl::Status PrepareUpdate(BakeParams& params) {
  if (params.update_from.empty()) return absl::OkStatus();
  std::error_code ec;
  const std::filesystem::path from = std::filesystem::absolute(params.update_from, ec);
  if (ec) return absl::InvalidArgumentError(absl::StrCat("--update: ", ec.message()));
  params.update_from = from.lexically_normal().string();
  if (absl::Status s = CheckUpdateSource(params.update_from, params); !s.ok()) return s;
  return CheckOldScene(params.update_from);
}

absl::StatusOr<bool> CopyIfUnchanged(const std::string& scene, const BakeParams& params,
                                     const std::filesystem::path& out) {
  const std::filesystem::path from = params.update_from;
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(from);
  if (!info.ok()) return info.status();
  absl::StatusOr<Scene> loaded = LoadScene(scene);
  if (!loaded.ok()) return loaded.status();
  if (StoreSceneHash(*info, *loaded) != info->scene_hash) return false;
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<ScopedDir> tmp = ScopedDir::CreateBeside(out, "update");
  if (!tmp.ok()) return tmp.status();
  const std::filesystem::path copy = tmp->path() / "store.wbk";
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(from, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const std::filesystem::path rel = std::filesystem::relative(it->path(), from, ec);
    if (!params.keep_staging && *rel.begin() == store::kStaging) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_directory(ec)) {
      std::filesystem::create_directories(copy / rel, ec);
    } else {
      std::filesystem::create_directories((copy / rel).parent_path(), ec);
      if (!ec) std::filesystem::copy_file(it->path(), copy / rel, ec);
    }
    if (ec) break;
  }
  if (ec)
    return absl::InternalError(
        absl::StrCat("--update: copying ", from.string(), ": ", ec.message()));
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(copy);
  if (!attrs.ok()) return attrs.status();
  (*attrs)["scene"] = RecordedSceneName(scene);
  const int64_t rows = attrs->value("S", int64_t{0}), columns = attrs->value("M", int64_t{0});
  (*attrs)["update"] = {
      {"from", from.string()},
      {"mode", params.update_exact ? "exact" : "local"},
      {"rows", rows},
      {"rows_reused", rows},
      {"rows_patched", 0},
      {"rows_rebaked", 0},
      {"columns", columns},
      {"columns_recomputed", 0},
      {"columns_depth_searched", 0},
      {"unchanged_scene", "the scene hashes as the old store's: its files were copied"},
      {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
  if (absl::Status s = WriteAttrs(copy, *attrs); !s.ok()) return s;
  if (absl::Status s = PublishStore(copy, out); !s.ok()) return s;
  return true;
}

absl::Status RecordUpdateTimes(const std::filesystem::path& store, double seconds,
                               double baking_seconds) {
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  if (!attrs.ok()) return attrs.status();
  if (!attrs->contains("update")) return absl::OkStatus();
  nlohmann::json& u = (*attrs)["update"];
  u["seconds"] = seconds;
  u["baking_seconds"] = baking_seconds;
  const double worked = u.value("rows_rebaked", 0.0) + u.value("rows_patched", 0.0),
               reused = u.value("rows_reused", 0.0);
  // The phase's seconds per row it traced or patched, times the rows it
  // copied: a row near the change costs more than most (it holds the
  // edit's silhouettes), so this errs low. Unknown when no row was worked.
  if (worked > 0) u["estimated_seconds_saved"] = baking_seconds / worked * reused;
  return WriteAttrs(store, *attrs);
}

std::string UpdateSummary(const std::filesystem::path& store) {
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  if (!attrs.ok() || !attrs->contains("update")) return {};
  const nlohmann::json& u = (*attrs)["update"];
  std::string line =
      absl::StrFormat("update (%s) from %s: %lld of %lld rows reused, %lld rebaked",
                      u.value("mode", ""), u.value("from", ""), u.value("rows_reused", 0LL),
                      u.value("rows", 0LL), u.value("rows_rebaked", 0LL));
  if (u.value("rows_patched", 0LL) > 0)
    absl::StrAppendFormat(&line, ", %lld patched", u.value("rows_patched", 0LL));
  if (u.contains("columns_recomputed"))
    absl::StrAppendFormat(&line, ", %lld of %lld columns recomputed",
                          u.value("columns_recomputed", 0LL), u.value("columns", 0LL));
  if (u.value("mode", "") == "local" && u.value("columns_recomputed", 0LL) > 0)
    absl::StrAppendFormat(&line, " (%lld searched for their depth)",
                          u.value("columns_depth_searched", 0LL));
  if (u.contains("estimated_seconds_saved"))
    absl::StrAppendFormat(&line, ", ~%.1f s of tracing saved",
                          u.value("estimated_seconds_saved", 0.0));
  if (u.contains("full_bake"))
    absl::StrAppend(&line, " (full bake: ", u.value("full_bake", ""), ")");
  return line;
}

}  // namespace wavebake::driver
