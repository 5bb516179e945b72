#pragma once
// `eval --reference` of a store with diffuse bounces, or of any diffuse store
// against a reference with bounces (`eval --bounces B`): the reference is the
// path tracer (runtime/reference/path_reference.h) when it has bounces, the
// direct reference otherwise; the uncompressed answer is dense T₀ retraced
// (runtime/reference/dense_trace.h) with the store's bounces added by the
// bake's own gather operator (core/bake/bake_gather.h: T = Σ_b G^b T₀ acts on
// the spatial index, so it applies to the relit image as to the rows), and
// dense T₀ alone is reported beside it: what leaving the bounces out costs.
#include "absl/status/statusor.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/store_relight.h"

namespace wavebake {

// The bounces a finished store holds: params.bounces, or for `auto` the
// count the bake chose (its .zattrs "bounces"/"count").
int StoreBounces(const StoreInfo& info);

// Evaluate (runtime/reference/eval.h) for a diffuse cube-domain store, env
// already turned. Errors: options.bounces above kMaxBounces (naming
// "bounces"), then Evaluate's.
absl::StatusOr<EvalReport> EvaluateBounces(OpenedStore& store, const EnvMap& env, int terms,
                                           const EvalOptions& options);

}  // namespace wavebake
