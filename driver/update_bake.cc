#include "driver/update_bake.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "storage/zarr_group.h"
#include "worker/row_reuse.h"

namespace wavebake::driver {

absl::Status PrepareUpdate(BakeParams& params) {
  if (params.update_from.empty()) return absl::OkStatus();
  std::error_code ec;
  const std::filesystem::path from = std::filesystem::absolute(params.update_from, ec);
  if (ec) return absl::InvalidArgumentError(absl::StrCat("--update: ", ec.message()));
  params.update_from = from.lexically_normal().string();
  return CheckUpdateSource(params.update_from, params);
}

absl::Status RecordUpdateTimes(const std::filesystem::path& store, double seconds,
                               double baking_seconds) {
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  if (!attrs.ok()) return attrs.status();
  if (!attrs->contains("update")) return absl::OkStatus();
  nlohmann::json& u = (*attrs)["update"];
  u["seconds"] = seconds;
  u["baking_seconds"] = baking_seconds;
  const double rebaked = u.value("rows_rebaked", 0.0), reused = u.value("rows_reused", 0.0);
  // Per rebaked row as the phase went; a row near the change costs more than
  // most (it has the edit's silhouettes), so this errs low. Unknown without
  // a rebaked row.
  if (rebaked > 0) u["estimated_seconds_saved"] = baking_seconds / rebaked * reused;
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
  if (u.contains("estimated_seconds_saved"))
    absl::StrAppendFormat(&line, ", ~%.1f s of tracing saved",
                          u.value("estimated_seconds_saved", 0.0));
  if (u.contains("full_bake"))
    absl::StrAppend(&line, " (full bake: ", u.value("full_bake", ""), ")");
  return line;
}

}  // namespace wavebake::driver
