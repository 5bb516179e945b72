#pragma once
// A BakeRequest (wavebake.v1) and the core parameters it stands for. The
// coordinator normalizes every submitted request with it, workers turn the
// request of a leased task back into BakeParams, and clients build requests
// from their flags: worker/ and coordinator/ meet only through proto/
// (DESIGN.md §6), so this is the one place that knows the mapping.
//
// Normalizing checks a request field by field and fills in the defaults of
// DESIGN.md §5, so a stored job always shows its effective parameters. Every
// error is INVALID_ARGUMENT and its message starts with the field path (§4),
// e.g. "light_res: 33 is not a power of two in 8..256". A request that
// normalizes is one every worker can bake: the core checks
// (ValidateBakeParams, ParseLayout) run too.
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "wavebake.pb.h"

namespace wavebake {

inline constexpr int kDefaultMaxAttempts = 3;

absl::Status NormalizeBakeRequest(v1::BakeRequest& request);

// The core parameters of a request (normalized on the way: defaults apply).
absl::StatusOr<BakeParams> ToBakeParams(const v1::BakeRequest& request);

// The request fields of `params` (no scene, tile_size and column_group
// included, ray_epsilon has no field and must be 0). ToBakeParams of the
// result gives `params` back.
v1::BakeRequest ToBakeRequest(const BakeParams& params);

// "builtin:NAME" or "NAME" -> "NAME"; empty if the request has no built-in.
std::string BuiltinSceneName(const v1::BakeRequest& request);

// Where a job's store is built before FINALIZE renames it to `store_path`
// (both relative to the store root): ".<store_path>.partial". Workers write
// staging and the final arrays there, so the output path only ever holds a
// finished store (DESIGN.md §4: nothing half-written is left behind); the
// coordinator's cleanup removes it. The leading dot keeps it apart from every
// output_name, which may not start with one.
std::string PartialStorePath(const std::string& store_path);

// The file the planner puts into a job's partial directory when it reserves
// it. Workers run a job's tasks only while it is there, and a worker whose
// task was stopped (its lease cancelled) removes a partial directory without
// it: the job ended, the coordinator's cleanup removed the directory, and the
// stopped task recreated part of it before it noticed. FINALIZE removes the
// marker after the rename, before the job is DONE.
inline constexpr char kPartialMarker[] = ".wavebake-partial";

}  // namespace wavebake
