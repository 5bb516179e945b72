#pragma once
// The driver's side of an update bake (`bake NEW --update OLD.wbk`,
// worker/tiles/row_reuse.h): the old store is checked before anything is written
// (a refused update leaves every file as it was), and the finished store's
// .zattrs "update" record gets the times the workers cannot know.
#include <filesystem>
#include <string>

#include "absl/status/status.h"
#include "core/bake/bake_params.h"

namespace wavebake::driver {

// params.update_from made absolute and checked (CheckUpdateSource,
// CheckOldScene): errors name --update and what the old store lacks, the
// first parameter that differs, or its scene that no longer loads here.
absl::Status PrepareUpdate(BakeParams& params);

// An update whose scene hashes as the old store's (same content, same
// parameters: CheckUpdateSource passed) rebakes nothing: the old store's
// files are copied (staging/ only if params.keep_staging), its "scene"
// renamed as this bake would record it, an "update" record added, and the
// copy published at `out`. Returns false (and writes nothing) when the
// scene differs; the bake then runs.
absl::StatusOr<bool> CopyIfUnchanged(const std::string& scene, const BakeParams& params,
                                     const std::filesystem::path& out);

// Adds the update's wall time, its BAKE_TILE phase's, and an estimate of the
// time saved (the phase's time per traced or patched row times the rows
// copied) to the
// "update" record of `store` (a finished store, not yet published).
absl::Status RecordUpdateTimes(const std::filesystem::path& store, double seconds,
                               double baking_seconds);

// One line for the command line: rows reused and rebaked, coefficients
// recomputed, seconds, or why it was a full bake. Empty if `store` has no record.
std::string UpdateSummary(const std::filesystem::path& store);

}  // namespace wavebake::driver
