#include "core/bake/bake_param_words.h"

#include <charconv>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_params_io.h"
#include "core/layouts/layout.h"

namespace wavebake {
namespace {

// A parsed name into `out`; the error keeps the parser's field name, with
// `prefix` for the two filters (row_filter, column_filter).
template <typename T>
absl::Status Set(absl::StatusOr<T> parsed, T& out, const char* prefix = "") {
  if (!parsed.ok())
    return absl::InvalidArgumentError(absl::StrCat(prefix, parsed.status().message()));
  out = *parsed;
  return absl::OkStatus();
}

absl::Status ParseBits(const std::string& bits, int& out) {
  if (bits == "auto") return absl::OkStatus();  // 0, the default
  const char* end = bits.data() + bits.size();
  auto [ptr, ec] = std::from_chars(bits.data(), end, out);
  if (ec != std::errc() || ptr != end || out == 0)
    return absl::InvalidArgumentError(absl::StrCat("bits: '", bits, "' is not 2..16 or auto"));
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<BakeParams> ParseBakeParamWords(BakeParams p, const BakeParamWords& w) {
  if (w.allow_uv_overlap) {
    absl::StatusOr<std::string> layout = WithUvOverlapAllowed(p.layout);
    if (!layout.ok()) return layout.status();
    p.layout = *layout;
  }
  if (w.refine != "on" && w.refine != "off")
    return absl::InvalidArgumentError(absl::StrCat("refine: '", w.refine, "' is not on or off"));
  p.refine = w.refine == "on";
  for (absl::Status s : {Set(ParseWaveletFilter(w.row_filter), p.row_filter, "row_"),
                         Set(ParseColumnMode(w.column_mode), p.column_mode),
                         Set(ParseWaveletFilter(w.column_filter), p.column_filter, "column_"),
                         Set(ParseErrorScope(w.error_scope), p.error_scope),
                         Set(ParseLevelScaling(w.level_scaling), p.level_scaling),
                         Set(ParseTransport(w.transport), p.transport),
                         Set(ParseLightDomain(w.light_domain), p.light_domain),
                         ParseBits(w.bits, p.bits), Set(ParseBounces(w.bounces), p.bounces)})
    if (!s.ok()) return s;
  if (absl::Status s = ValidateBakeParams(p); !s.ok()) return s;
  return p;
}

}  // namespace wavebake
