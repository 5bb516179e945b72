#include "core/bake/bake_params_io.h"

#include "absl/strings/str_cat.h"
#include "core/util/power_of_two.h"

namespace wavebake {

std::string_view ToString(ColumnMode m) {
  switch (m) {
    case ColumnMode::k2d:
      return "2d";
    case ColumnMode::kFull:
      return "full";
    case ColumnMode::kAdaptive:
      return "adaptive";
  }
  return "?";
}

std::string_view ToString(WaveletFilter f) {
  switch (f) {
    case WaveletFilter::kHaar:
      return "haar";
    case WaveletFilter::kDaub4:
      return "daub4";
    case WaveletFilter::kLeGall53:
      return "legall53";
    case WaveletFilter::kCdf97:
      return "cdf97";
  }
  return "?";
}

std::string_view ToString(ErrorScope s) { return s == ErrorScope::kMatrix ? "matrix" : "column"; }

std::string_view ToString(LevelScaling s) {
  return s == LevelScaling::kUniform ? "uniform" : "paper";
}

std::string_view ToString(Transport t) {
  return t == Transport::kDiffuse ? "diffuse" : "visibility";
}

absl::StatusOr<Transport> ParseTransport(std::string_view s) {
  if (s == "diffuse") return Transport::kDiffuse;
  if (s == "visibility") return Transport::kVisibility;
  return absl::InvalidArgumentError(
      absl::StrCat("transport: unknown transport '", std::string(s), "' (diffuse|visibility)"));
}

absl::StatusOr<ColumnMode> ParseColumnMode(std::string_view s) {
  for (ColumnMode m : {ColumnMode::k2d, ColumnMode::kFull, ColumnMode::kAdaptive})
    if (s == ToString(m)) return m;
  return absl::InvalidArgumentError(
      absl::StrCat("column_mode: unknown mode '", std::string(s), "' (adaptive|full|2d)"));
}

absl::StatusOr<WaveletFilter> ParseWaveletFilter(std::string_view s) {
  for (WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4, WaveletFilter::kLeGall53,
                          WaveletFilter::kCdf97})
    if (s == ToString(f)) return f;
  return absl::InvalidArgumentError(
      absl::StrCat("filter: unknown filter '", std::string(s), "' (haar|daub4|legall53|cdf97)"));
}

absl::StatusOr<ErrorScope> ParseErrorScope(std::string_view s) {
  if (s == "matrix") return ErrorScope::kMatrix;
  if (s == "column") return ErrorScope::kColumn;
  return absl::InvalidArgumentError(
      absl::StrCat("error_scope: unknown scope '", std::string(s), "' (matrix|column)"));
}

absl::StatusOr<LevelScaling> ParseLevelScaling(std::string_view s) {
  if (s == "uniform") return LevelScaling::kUniform;
  if (s == "paper") return LevelScaling::kPaper;
  return absl::InvalidArgumentError(
      absl::StrCat("level_scaling: unknown scaling '", std::string(s), "' (uniform|paper)"));
}

absl::Status ValidateBakeParams(const BakeParams& p) {
  // Debian's Abseil has its own string_view, so views are passed as strings.
  auto bad = [](const char* field, const auto&... msg) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": ", msg...));
  };
  if (!IsPowerOfTwoIn(p.light_res, 8, 256))
    return bad("light_res", p.light_res, " is not a power of two in 8..256");
  if (absl::Status s = ValidateLightDomain(p.light_domain); !s.ok()) return s;
  if (p.supersample < 1 || p.supersample > 256)
    return bad("supersample", p.supersample, " is outside 1..256");
  if (p.row_filter != WaveletFilter::kHaar && p.row_filter != WaveletFilter::kDaub4)
    return bad("row_filter", std::string(ToString(p.row_filter)),
               " is not a row filter (haar|daub4)");
  // The triple product's tripling coefficients are those of the Haar basis.
  if (p.transport == Transport::kVisibility && p.row_filter != WaveletFilter::kHaar)
    return bad("row_filter", "a visibility transport needs haar rows (the Haar triple product)");
  // The tripling coefficients are those of the six-face cube's Haar basis.
  if (p.transport == Transport::kVisibility && p.light_domain.is_plane())
    return bad("light_domain",
               "a visibility transport needs the cube (the triple product is "
               "over the whole sphere of directions)");
  if (p.column_filter == WaveletFilter::kDaub4)
    return bad("column_filter", "daub4 is a row filter (haar|legall53|cdf97)");
  if (!(p.target_error >= 0) || p.target_error > 1)
    return bad("target_error", p.target_error, " is outside [0, 1]");
  if (p.column_terms < 0) return bad("column_terms", p.column_terms, " is negative");
  if (p.column_terms == 0 && p.target_error == 0)
    return bad("target_error", "0 keeps everything; give a positive target or --column-terms");
  if (p.bits != 0 && (p.bits < 2 || p.bits > 16))
    return bad("bits", p.bits, " is outside 2..16 (or auto)");
  if (!IsPowerOfTwoIn(p.tile_size, 1, 256))
    return bad("tile_size", p.tile_size, " is not a power of two up to 256");
  if (p.update_exact && p.update_from.empty())
    return absl::InvalidArgumentError("update_exact: needs update_from (the store to update)");
  if (p.column_group < 0 || p.column_group > 65536)
    return bad("column_group", p.column_group, " is outside 1..65536 (or 0: the plan's)");
  if (!(p.ray_epsilon >= 0)) return bad("ray_epsilon", p.ray_epsilon, " is negative");
  return absl::OkStatus();
}

}  // namespace wavebake
