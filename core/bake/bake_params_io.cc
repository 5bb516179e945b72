#include "core/bake/bake_params_io.h"

#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_param_words.h"
#include "core/layouts/layout.h"
#include "core/util/power_of_two.h"

namespace wavebake {
namespace params {

// The layout is kept as spelled (a request's "camera" stays "camera"): the
// store records what was asked for.
absl::StatusOr<std::string> ParseLayoutSpelling(std::string_view s) {
  if (absl::Status st = ParseLayout(s).status(); !st.ok()) return st;
  return std::string(s);
}
std::string PrintLayout(const std::string& s) { return s; }
absl::StatusOr<std::string> ParseText(std::string_view s) { return std::string(s); }
absl::StatusOr<LightDomain> ParseDomainSpelling(std::string_view s) { return ParseLightDomain(s); }
std::string PrintDomain(const LightDomain& d) { return ToString(d); }

}  // namespace params

namespace {

using namespace params;  // NOLINT: the table's row types

template <class T>
std::string RangeText(const Number<T>& r) {
  std::string text;
  if constexpr (std::is_integral_v<T>)
    text = absl::StrCat(static_cast<long long>(r.lo), "..", static_cast<long long>(r.hi));
  else
    text = absl::StrCat("[", r.lo, ", ", r.hi, "]");
  if (!r.special.empty())
    absl::StrAppend(&text, r.special_is_word ? absl::StrCat(" (or ", std::string(r.special), ")")
                                             : absl::StrCat(" (or ", r.special_value, ": ",
                                                            std::string(r.special), ")"));
  return text;
}

// Each row's own range or words; the rules between rows follow in
// ValidateBakeParams.
struct CheckRow {
  const BakeParams& p;
  absl::Status status;

  template <class T>
  void operator()(const Number<T>& r) {
    const T v = p.*r.field;
    if (!status.ok() || (v == r.special_value && !r.special.empty())) return;
    const double d = static_cast<double>(v);
    const bool unbounded = r.hi == kInf || r.hi >= double(std::numeric_limits<int>::max());
    if (r.power_of_two && !(d >= r.lo && d <= r.hi && IsPowerOfTwo(static_cast<int>(v))))
      status = Bad(r.info, absl::StrCat(v, " is not a power of two in ", RangeText(r)));
    else if (!(d >= r.lo) && unbounded && r.lo == 0)
      status = Bad(r.info, absl::StrCat(v, " is negative"));
    else if (!(d >= r.lo && d <= r.hi))
      status = Bad(r.info, absl::StrCat(v, " is outside ", RangeText(r)));
  }
  template <class E>
  void operator()(const Words<E>& r) {
    if (status.ok() && WordOf(r.words, p.*r.field) == "?")
      status =
          Bad(r.info, absl::StrCat("not a ", std::string(r.info.name), " (", Joined(r.words), ")"));
  }
  void operator()(const Switch&) {}
  template <class T>
  void operator()(const Spelled<T>& r) {
    if (!status.ok()) return;
    if (absl::StatusOr<T> back = r.parse(r.print(p.*r.field)); !back.ok())
      status = back.status();  // the parsers name their field
  }

  static absl::Status Bad(const Info& info, const std::string& why) {
    return absl::InvalidArgumentError(absl::StrCat(std::string(info.name), ": ", why));
  }
};

}  // namespace

std::string_view ToString(ColumnMode m) { return WordOf<ColumnMode>(kColumnModes, m); }
std::string_view ToString(WaveletFilter f) {
  std::string_view w = WordOf<WaveletFilter>(kColumnFilters, f);
  return w != "?" ? w : WordOf<WaveletFilter>(kRowFilters, f);
}
std::string_view ToString(ErrorScope s) { return WordOf<ErrorScope>(kErrorScopes, s); }
std::string_view ToString(LevelScaling s) { return WordOf<LevelScaling>(kLevelScalings, s); }
std::string_view ToString(Transport t) { return WordOf<Transport>(kTransports, t); }

absl::StatusOr<ColumnMode> ParseColumnMode(std::string_view s) {
  return ParseWord<ColumnMode>("column_mode", kColumnModes, s);
}
absl::StatusOr<WaveletFilter> ParseWaveletFilter(std::string_view s) {
  if (s == "daub4") return WaveletFilter::kDaub4;
  absl::StatusOr<WaveletFilter> f = ParseWord<WaveletFilter>("filter", kColumnFilters, s);
  if (!f.ok())
    return absl::InvalidArgumentError(
        absl::StrCat("filter: unknown filter '", std::string(s), "' (haar|daub4|legall53|cdf97)"));
  return f;
}
absl::StatusOr<ErrorScope> ParseErrorScope(std::string_view s) {
  return ParseWord<ErrorScope>("error_scope", kErrorScopes, s);
}
absl::StatusOr<LevelScaling> ParseLevelScaling(std::string_view s) {
  return ParseWord<LevelScaling>("level_scaling", kLevelScalings, s);
}
absl::StatusOr<Transport> ParseTransport(std::string_view s) {
  return ParseWord<Transport>("transport", kTransports, s);
}

absl::Status ValidateBakeParams(const BakeParams& p) {
  CheckRow check{p, absl::OkStatus()};
  ForEach(check);
  if (!check.status.ok()) return check.status;
  auto bad = [](const char* field, const char* why) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": ", why));
  };
  // The triple product's tripling coefficients are those of the Haar basis.
  if (p.transport == Transport::kVisibility && p.row_filter != WaveletFilter::kHaar)
    return bad("row_filter", "a visibility transport needs haar rows (the Haar triple product)");
  // The tripling coefficients are those of the six-face cube's Haar basis.
  if (p.transport == Transport::kVisibility && p.light_domain.is_plane())
    return bad("light_domain",
               "a visibility transport needs the cube (the triple product is over the whole "
               "sphere of directions)");
  // The triple product keeps V and ρ apart (vollick-lessig-haar-triple-product.md
  // §1 Eq. 16 against Eq. 10): light that bounces off other surfaces depends on
  // their BRDF, so it cannot be folded into a visibility row.
  if (p.bounces != 0 && p.transport == Transport::kVisibility)
    return bad("bounces",
               "a visibility transport cannot hold interreflection: the triple product keeps "
               "visibility and the BRDF apart, and bounced light depends on both (bake "
               "--transport diffuse for bounces)");
  if (p.column_terms == 0 && p.target_error == 0)
    return bad("target_error", "0 keeps everything; give a positive target or --column-terms");
  if (p.update_exact && !p.updates())
    return absl::InvalidArgumentError(
        "update_exact: needs update_from or update_job (the store to update)");
  return absl::OkStatus();
}

}  // namespace wavebake
