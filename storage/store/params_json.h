#pragma once
// BakeParams ⇄ the "params" object of a store's root .zattrs (DESIGN.md §3:
// "job params"): every row of the table of bake parameters by its name and
// Record rule (core/bake/bake_param_table.h), words as the CLI spells them,
// bits as "auto" or the number.
#include <nlohmann/json.hpp>

#include "absl/status/statusor.h"
#include "core/bake/bake_param_table.h"

namespace wavebake {

nlohmann::json ToJson(const BakeParams& p);
// Every parameter of one stage (core/bake/bake_param_table.h), whatever the
// store records: e.g. what a staging's rows depend on.
nlohmann::json ToJson(const BakeParams& p, params::Stage stage);
// Errors name the field ("params.column_mode: ..."); the result is validated
// with ValidateBakeParams.
absl::StatusOr<BakeParams> BakeParamsFromJson(const nlohmann::json& j);

// An update keeps every recorded parameter but the scene: the first that
// differs between `have` (the old store's "params") and `want` (ToJson of
// the new bake's), worded "parameter light_res is 8 there and 16 here: ...";
// empty when they agree.
std::string FirstParameterDifference(const nlohmann::json& have, const nlohmann::json& want);

}  // namespace wavebake
