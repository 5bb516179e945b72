#include "driver/relight/relight_to_file.h"

#include <cmath>
#include <memory>
#include <vector>

#include "absl/strings/str_cat.h"
#include "core/products/brdf.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/store_relight.h"

namespace wavebake::driver {
namespace {

// The arguments both relights check before any work.
absl::Status CheckTermsAndRotation(int terms, double rotate_degrees) {
  if (terms <= 0)
    return absl::InvalidArgumentError(absl::StrCat("terms: ", terms, "; need at least 1"));
  if (!std::isfinite(rotate_degrees))
    return absl::InvalidArgumentError(absl::StrCat("rotate: ", rotate_degrees, " is not finite"));
  return absl::OkStatus();
}

// The environment as LoadEnvMap reads it, turned about +Y.
absl::StatusOr<EnvMap> LoadRotatedEnv(std::string_view env_spec, double rotate_degrees) {
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  if (rotate_degrees != 0) *env = Rotated(*env, rotate_degrees);
  return env;
}

}  // namespace

absl::Status RelightToFile(const std::filesystem::path& store, std::string_view env_spec, int terms,
                           double rotate_degrees, float exposure_stops,
                           const std::filesystem::path& out) {
  if (absl::Status s = CheckTermsAndRotation(terms, rotate_degrees); !s.ok()) return s;
  if (absl::Status s = CheckRelitPath(out); !s.ok()) return s;
  absl::StatusOr<EnvMap> env = LoadRotatedEnv(env_spec, rotate_degrees);
  if (!env.ok()) return env.status();
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  if (!opened.ok()) return opened.status();
  absl::StatusOr<std::vector<float>> rgb = RelightImage(*opened, *env, terms);
  if (!rgb.ok()) return rgb.status();
  return WriteRelit(*opened, *rgb, exposure_stops, out);
}

absl::Status RelightGlossyToFile(const std::filesystem::path& store, std::string_view env_spec,
                                 int terms, double rotate_degrees, float exposure_stops,
                                 const std::filesystem::path& out, const GlossyOptions& options) {
  if (absl::Status s = CheckTermsAndRotation(terms, rotate_degrees); !s.ok()) return s;
  absl::StatusOr<EnvMap> env = LoadRotatedEnv(env_spec, rotate_degrees);
  if (!env.ok()) return env.status();
  absl::StatusOr<std::unique_ptr<GlossyStore>> g = GlossyStore::Open(store, options);
  if (!g.ok()) return g.status();
  absl::StatusOr<std::vector<float>> rgb = (*g)->RelightImage(*env, terms);
  if (!rgb.ok()) return rgb.status();
  return WriteRelit((*g)->info(), (*g)->samples(), *rgb, exposure_stops, out);
}

absl::Status RelightStoreToFile(const std::filesystem::path& store, std::string_view env_spec,
                                int terms, double rotate_degrees, float exposure_stops,
                                const std::filesystem::path& out, const GlossyOptions& options) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  if (!info.ok()) return info.status();
  if (info->params.transport == Transport::kVisibility)
    return RelightGlossyToFile(store, env_spec, terms, rotate_degrees, exposure_stops, out,
                               options);
  absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(options.brdf);
  if (!brdf.ok()) return brdf.status();
  if ((*brdf)->Name() != "lambert") return CheckVisibilityStore(*info);
  if (options.eye)
    return absl::InvalidArgumentError(
        "view: a diffuse store is relit the same from every view; --view needs a visibility "
        "store and a glossy --brdf");
  return RelightToFile(store, env_spec, terms, rotate_degrees, exposure_stops, out);
}

}  // namespace wavebake::driver
