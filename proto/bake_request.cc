#include "proto/bake_request.h"

#include <cmath>
#include <filesystem>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/string_view.h"
#include "absl/strings/strip.h"
#include "core/bake/bake_params_io.h"
#include "core/layouts/layout.h"
#include "core/util/power_of_two.h"

namespace wavebake {
namespace {

absl::Status Bad(absl::string_view field, absl::string_view why) {
  return absl::InvalidArgumentError(absl::StrCat(field, ": ", why));
}

// The spelling is the core's (core/layouts/layout.h); the request keeps it as given
// ("camera" stays "camera", not "camera:64x64"), since the store records it.
absl::Status CheckLayout(std::string& layout) {
  if (layout.empty()) layout = "camera";
  return ParseLayout(layout).status();
}

absl::Status CheckChoice(absl::string_view field, std::string& value, absl::string_view fallback,
                         std::initializer_list<absl::string_view> choices) {
  if (value.empty()) value = std::string(fallback);
  for (absl::string_view c : choices) {
    if (value == c) return absl::OkStatus();
  }
  return Bad(field, absl::StrCat("\"", value, "\" is not one of ", absl::StrJoin(choices, ", ")));
}

absl::Status CheckLightDomain(std::string& domain) {
  if (domain.empty()) domain = "cube";
  return ParseLightDomain(domain).status();
}

absl::Status CheckScene(v1::BakeRequest& r) {
  const v1::SceneSource& scene = r.scene();
  switch (scene.source_case()) {
    case v1::SceneSource::kBuiltin: {
      const std::string name = BuiltinSceneName(r);
      if (name.empty() || name.size() > 64 ||
          name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") != name.npos) {
        return Bad("scene.builtin", absl::StrCat("\"", scene.builtin(), "\" is not builtin:NAME"));
      }
      return absl::OkStatus();
    }
    case v1::SceneSource::kUploaded: {
      const std::string& sha = scene.uploaded().sha256();
      if (sha.size() != 64 || sha.find_first_not_of("0123456789abcdef") != sha.npos) {
        return Bad("scene.uploaded.sha256", "must be 64 lowercase hex digits");
      }
      return absl::OkStatus();
    }
    default:
      return Bad("scene", "missing: give a builtin:NAME or an uploaded SceneRef");
  }
}

absl::Status CheckOutputName(v1::BakeRequest& r) {
  const std::string& name = r.output_name();
  if (name.empty()) return absl::OkStatus();  // the coordinator names it after the job
  if (name.size() > 128 || name.front() == '.' ||
      name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") !=
          name.npos) {
    return Bad(
        "output_name",
        absl::StrCat("\"", name, "\" must be 1..128 of [A-Za-z0-9._-], not starting with '.'"));
  }
  return absl::OkStatus();
}

absl::Status CheckNumbers(v1::BakeRequest& r) {
  // An unset field (proto3: 0) takes the core's default (core/bake/bake_params.h).
  const BakeParams defaults;
  if (r.light_res() == 0) r.set_light_res(defaults.light_res);
  if (!IsPowerOfTwoIn(r.light_res(), 8, 256)) {
    return Bad("light_res", absl::StrCat(r.light_res(), " is not a power of two in 8..256"));
  }
  if (r.supersample() == 0) r.set_supersample(defaults.supersample);
  if (r.supersample() < 1 || r.supersample() > 256) {
    return Bad("supersample", absl::StrCat(r.supersample(), " is not in 1..256"));
  }
  if (r.target_error() == 0) r.set_target_error(defaults.target_error);
  if (!std::isfinite(r.target_error()) || r.target_error() < 0 || r.target_error() > 1) {
    return Bad("target_error", absl::StrCat(r.target_error(), " is not in (0, 1]"));
  }
  if (r.column_terms() < 0) {
    return Bad("column_terms", absl::StrCat(r.column_terms(), " is negative"));
  }
  if (r.bits() != 0 && (r.bits() < 2 || r.bits() > 16)) {
    return Bad("bits", absl::StrCat(r.bits(), " is not 0 (auto) or 2..16"));
  }
  if (!r.has_seed()) r.set_seed(defaults.seed);
  if (r.tile_size() == 0) r.set_tile_size(defaults.tile_size);
  if (!IsPowerOfTwoIn(r.tile_size(), 4, 256)) {
    return Bad("tile_size", absl::StrCat(r.tile_size(), " is not a power of two in 4..256"));
  }
  if (r.column_group() < 0 || r.column_group() > 65536) {  // 0: the plan's
    return Bad("column_group",
               absl::StrCat(r.column_group(), " is not in 1..65536 (or 0: the plan's)"));
  }
  if (r.max_attempts() == 0) r.set_max_attempts(kDefaultMaxAttempts);
  if (r.max_attempts() < 1 || r.max_attempts() > 100) {
    return Bad("max_attempts", absl::StrCat(r.max_attempts(), " is not in 1..100"));
  }
  return absl::OkStatus();
}

// The core parameters of a request whose fields are each in range.
BakeParams ParamsOf(const v1::BakeRequest& r) {
  BakeParams p;
  p.light_res = r.light_res();
  p.layout = r.layout();
  p.supersample = r.supersample();
  p.row_filter = r.row_filter() == "daub4" ? WaveletFilter::kDaub4 : WaveletFilter::kHaar;
  p.column_mode = r.column_mode() == "2d"     ? ColumnMode::k2d
                  : r.column_mode() == "full" ? ColumnMode::kFull
                                              : ColumnMode::kAdaptive;
  p.column_filter = r.column_filter() == "legall53" ? WaveletFilter::kLeGall53
                    : r.column_filter() == "cdf97"  ? WaveletFilter::kCdf97
                                                    : WaveletFilter::kHaar;
  p.target_error = r.target_error();
  p.error_scope = r.error_scope() == "column" ? ErrorScope::kColumn : ErrorScope::kMatrix;
  p.column_terms = r.column_terms();
  p.bits = r.bits();
  p.level_scaling = r.level_scaling() == "paper" ? LevelScaling::kPaper : LevelScaling::kUniform;
  p.transport = r.transport() == "visibility" ? Transport::kVisibility : Transport::kDiffuse;
  p.light_domain = ParseLightDomain(r.light_domain()).value_or(LightDomain{});
  p.seed = r.seed();
  p.tile_size = r.tile_size();
  p.column_group = r.column_group();
  p.keep_staging = r.keep_staging();
  p.update_from = r.update_from();
  p.update_exact = r.update_exact();
  p.refine = r.refine() != "off";
  return p;
}

}  // namespace

std::string BuiltinSceneName(const v1::BakeRequest& request) {
  if (!request.scene().has_builtin()) return {};
  absl::string_view name = request.scene().builtin();
  absl::ConsumePrefix(&name, "builtin:");
  return std::string(name);
}

absl::Status NormalizeBakeRequest(v1::BakeRequest& r) {
  const bool refine_unset = r.refine().empty();
  for (absl::Status s :
       {CheckScene(r), CheckNumbers(r), CheckLayout(*r.mutable_layout()),
        CheckChoice("column_mode", *r.mutable_column_mode(), "adaptive",
                    {"adaptive", "full", "2d"}),
        CheckChoice("column_filter", *r.mutable_column_filter(), "haar",
                    {"haar", "legall53", "cdf97"}),
        CheckChoice("row_filter", *r.mutable_row_filter(), "haar", {"haar", "daub4"}),
        CheckChoice("error_scope", *r.mutable_error_scope(), "matrix", {"matrix", "column"}),
        CheckChoice("level_scaling", *r.mutable_level_scaling(), "uniform", {"uniform", "paper"}),
        CheckChoice("transport", *r.mutable_transport(), "diffuse", {"diffuse", "visibility"}),
        CheckChoice("refine", *r.mutable_refine(), "on", {"on", "off"}),
        CheckLightDomain(*r.mutable_light_domain()), CheckOutputName(r)}) {
    if (!s.ok()) return s;
  }
  // Refinement follows the cube's faces and integrates cosines: a plane
  // domain and a visibility transport default to brute force and cannot ask
  // for refinement.
  const bool plane = ParseLightDomain(r.light_domain())->is_plane();
  if (plane || r.transport() == "visibility") {
    if (!refine_unset && r.refine() == "on")
      return Bad("refine", plane ? "\"on\" needs the cube light domain (plane domains trace "
                                   "every texel)"
                                 : "\"on\" needs the diffuse transport (visibility rows are "
                                   "traced by brute force)");
    r.set_refine("off");
  }
  // The fields one by one are fine; the core's own rules have the last word.
  return ValidateBakeParams(ParamsOf(r));
}

absl::StatusOr<BakeParams> ToBakeParams(const v1::BakeRequest& request) {
  v1::BakeRequest r = request;
  if (absl::Status s = NormalizeBakeRequest(r); !s.ok()) return s;
  return ParamsOf(r);
}

v1::BakeRequest ToBakeRequest(const BakeParams& p) {
  v1::BakeRequest r;
  r.set_light_res(p.light_res);
  r.set_layout(p.layout);
  r.set_supersample(p.supersample);
  r.set_column_mode(std::string(ToString(p.column_mode)));
  r.set_column_filter(std::string(ToString(p.column_filter)));
  r.set_target_error(p.target_error);
  r.set_error_scope(std::string(ToString(p.error_scope)));
  r.set_column_terms(p.column_terms);
  r.set_bits(p.bits);
  r.set_level_scaling(std::string(ToString(p.level_scaling)));
  r.set_transport(std::string(ToString(p.transport)));
  if (p.light_domain.is_plane()) r.set_light_domain(ToString(p.light_domain));
  r.set_seed(p.seed);
  r.set_row_filter(std::string(ToString(p.row_filter)));
  r.set_tile_size(p.tile_size);
  r.set_column_group(p.column_group);
  r.set_keep_staging(p.keep_staging);
  r.set_update_from(p.update_from);
  r.set_update_exact(p.update_exact);
  r.set_refine(p.refines() ? "on" : "off");
  return r;
}

std::string PartialStorePath(const std::string& store_path) {
  const std::filesystem::path p(store_path);
  return (p.parent_path() / absl::StrCat(".", p.filename().string(), ".partial")).string();
}

}  // namespace wavebake
