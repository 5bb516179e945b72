#include "storage/params_json.h"

#include <string>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_params_io.h"

namespace wavebake {
namespace {

absl::Status Bad(const char* field, const std::string& why) {
  return absl::InvalidArgumentError(absl::StrCat("params.", field, ": ", why));
}

// Reads j[field] into *out when it has the right JSON type.
absl::Status GetInt(const nlohmann::json& j, const char* field, int* out) {
  if (!j.contains(field) || !j[field].is_number_integer())
    return Bad(field, "missing or not an integer");
  *out = j[field].get<int>();
  return absl::OkStatus();
}
absl::Status GetNumber(const nlohmann::json& j, const char* field, double* out) {
  if (!j.contains(field) || !j[field].is_number()) return Bad(field, "missing or not a number");
  *out = j[field].get<double>();
  return absl::OkStatus();
}
absl::Status GetString(const nlohmann::json& j, const char* field, std::string* out) {
  if (!j.contains(field) || !j[field].is_string()) return Bad(field, "missing or not a string");
  *out = j[field].get<std::string>();
  return absl::OkStatus();
}

// An enum spelled as core/bake/bake_params_io.h spells it.
template <class E, class Parse>
absl::Status GetEnum(const nlohmann::json& j, const char* field, Parse parse, E* out) {
  std::string s;
  if (absl::Status st = GetString(j, field, &s); !st.ok()) return st;
  absl::StatusOr<E> v = parse(s);
  if (!v.ok()) return Bad(field, std::string(v.status().message()));
  *out = *v;
  return absl::OkStatus();
}

absl::Status GetBits(const nlohmann::json& j, int* bits) {
  if (j.contains("bits") && j["bits"] == "auto") {
    *bits = 0;
    return absl::OkStatus();
  }
  return GetInt(j, "bits", bits);
}

}  // namespace

nlohmann::json ToJson(const BakeParams& p) {
  nlohmann::json j = {{"light_res", p.light_res},
                      {"layout", p.layout},
                      {"supersample", p.supersample},
                      {"row_filter", std::string(ToString(p.row_filter))},
                      {"column_mode", std::string(ToString(p.column_mode))},
                      {"column_filter", std::string(ToString(p.column_filter))},
                      {"target_error", p.target_error},
                      {"error_scope", std::string(ToString(p.error_scope))},
                      {"column_terms", p.column_terms},
                      {"bits", p.bits == 0 ? nlohmann::json("auto") : nlohmann::json(p.bits)},
                      {"level_scaling", std::string(ToString(p.level_scaling))},
                      {"seed", p.seed},
                      {"tile_size", p.tile_size},
                      {"column_group", p.column_group},
                      {"ray_epsilon", p.ray_epsilon}};
  // Absent means brute force: what every store baked before refinement
  // existed holds, so a --refine off store keeps their exact bytes.
  if (p.refines()) j["refine"] = "on";
  // Only a visibility transport and a plane light domain are spelled out: a
  // default store's .zattrs stays byte-identical to the stores written before
  // the fields existed.
  if (p.transport != Transport::kDiffuse) j["transport"] = std::string(ToString(p.transport));
  if (p.light_domain.is_plane()) j["light_domain"] = ToString(p.light_domain);
  // Absent means direct light only, so 0-bounce stores keep their bytes.
  if (p.bounces != 0) {
    j["bounces"] = p.bounces == kAutoBounces ? nlohmann::json("auto") : nlohmann::json(p.bounces);
    j["gather_rays"] = p.gather_rays;
  }
  return j;
}

absl::StatusOr<BakeParams> BakeParamsFromJson(const nlohmann::json& j) {
  if (!j.is_object()) return absl::InvalidArgumentError("params: not an object");
  BakeParams p;
  double target = 0, epsilon = 0;
  for (absl::Status s : {
           GetInt(j, "light_res", &p.light_res),
           GetString(j, "layout", &p.layout),
           GetInt(j, "supersample", &p.supersample),
           GetEnum(j, "row_filter", ParseWaveletFilter, &p.row_filter),
           GetEnum(j, "column_mode", ParseColumnMode, &p.column_mode),
           GetEnum(j, "column_filter", ParseWaveletFilter, &p.column_filter),
           GetNumber(j, "target_error", &target),
           GetEnum(j, "error_scope", ParseErrorScope, &p.error_scope),
           GetInt(j, "column_terms", &p.column_terms),
           GetBits(j, &p.bits),
           GetEnum(j, "level_scaling", ParseLevelScaling, &p.level_scaling),
           GetInt(j, "tile_size", &p.tile_size),
           GetInt(j, "column_group", &p.column_group),
           GetNumber(j, "ray_epsilon", &epsilon),
       }) {
    if (!s.ok()) return s;
  }
  if (!j.contains("seed") || !j["seed"].is_number_unsigned())
    return Bad("seed", "missing or not an unsigned integer");
  p.seed = j["seed"].get<uint64_t>();
  if (j.contains("transport")) {  // absent: diffuse (stores before the field)
    if (absl::Status s = GetEnum(j, "transport", ParseTransport, &p.transport); !s.ok()) return s;
  }
  p.refine = false;
  if (j.contains("refine")) {
    if (j["refine"] != "on" && j["refine"] != "off") return Bad("refine", "not \"on\" or \"off\"");
    p.refine = j["refine"] == "on";
  }
  if (j.contains("light_domain")) {  // absent: the cube (stores before the field)
    if (absl::Status s = GetEnum(j, "light_domain", ParseLightDomain, &p.light_domain); !s.ok())
      return s;
  }
  if (j.contains("bounces")) {  // absent: 0 (stores before the field)
    absl::Status b = j["bounces"].is_string() ? GetEnum(j, "bounces", ParseBounces, &p.bounces)
                                              : GetInt(j, "bounces", &p.bounces);
    if (b.ok()) b = GetInt(j, "gather_rays", &p.gather_rays);
    if (!b.ok()) return b;
  }
  p.target_error = target;
  p.ray_epsilon = static_cast<float>(epsilon);
  if (absl::Status s = ValidateBakeParams(p); !s.ok())
    return absl::InvalidArgumentError(absl::StrCat("params.", s.message()));
  return p;
}

}  // namespace wavebake
