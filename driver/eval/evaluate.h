#pragma once
// `wavebake eval STORE --env ENV --reference` (DESIGN.md §5) as one call: the
// driver reads the environment, runtime/reference/eval.h measures the store
// against the independent reference.
#include <filesystem>
#include <string_view>

#include "absl/status/statusor.h"
#include "runtime/reference/eval.h"

namespace wavebake::driver {

// ENV as LoadEnvMap reads it. Errors: the env spec, then Evaluate's.
absl::StatusOr<EvalReport> Evaluate(const std::filesystem::path& store, std::string_view env_spec,
                                    int terms, const EvalOptions& options = {});

}  // namespace wavebake::driver
