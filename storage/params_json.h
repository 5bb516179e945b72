#pragma once
// BakeParams ⇄ the "params" object of a store's root .zattrs (DESIGN.md §3:
// "job params"): every field by its name, enum values spelled as the CLI
// spells them (core/bake/bake_params_io.h), bits as "auto" or the number.
#include <nlohmann/json.hpp>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"

namespace wavebake {

nlohmann::json ToJson(const BakeParams& p);
// Errors name the field ("params.column_mode: ..."); the result is validated
// with ValidateBakeParams.
absl::StatusOr<BakeParams> BakeParamsFromJson(const nlohmann::json& j);

}  // namespace wavebake
