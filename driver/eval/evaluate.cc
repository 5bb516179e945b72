#include "driver/eval/evaluate.h"

#include "runtime/env/env_map.h"

namespace wavebake::driver {

absl::StatusOr<EvalReport> Evaluate(const std::filesystem::path& store, std::string_view env_spec,
                                    int terms, const EvalOptions& options) {
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  return wavebake::Evaluate(store, *env, terms, options);
}

}  // namespace wavebake::driver
