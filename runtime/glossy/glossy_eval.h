#pragma once
// `wavebake eval STORE --env ENV --reference --brdf B` on a visibility store
// (DESIGN.md §5): the triple-product relighting at `terms` lighting terms
// (runtime/glossy/glossy_store.h), and the dense visibility path (every V row
// retraced, the BRDF texel by texel, the product in the pixel basis:
// runtime/reference/dense_trace.h TraceDenseGlossy), each against the Monte-Carlo
// reference traced with the same BRDF and views (runtime/reference/reference.h), which
// shares no code with the triple product.
#include <filesystem>
#include <string_view>

#include "absl/status/statusor.h"
#include "runtime/reference/eval.h"

namespace wavebake {

// Errors as Evaluate's; the store must hold visibility.
absl::StatusOr<EvalReport> EvaluateGlossy(const std::filesystem::path& store,
                                          std::string_view env_spec, int terms,
                                          const EvalOptions& options);

}  // namespace wavebake
