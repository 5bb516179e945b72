#pragma once
// The one table of bake parameters (DESIGN.md §5): each row gives a
// parameter's name — the BakeParams field, the BakeRequest field, the key of
// the store's .zattrs "params" and the field that errors name — its
// command-line flag and help, its range or words, and when the store records
// it. The command-line flags (cli/bake_flags.cc), the request's conversion
// (proto/bake_request.cc), the .zattrs writer and reader
// (storage/store/params_json.cc), the staging's trace record (worker/tiles/recode.cc) and
// the validation (core/bake/bake_params_io.cc) are loops over these rows, so
// a new parameter is a BakeParams field, one row here and, if clients may set
// it over gRPC, a BakeRequest field of the same name.
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"

namespace wavebake::params {

// What a parameter changes.
enum class Stage {
  kTrace,    // the traced rows or their staging: a staging is reused only when these match
  kColumns,  // the column coding and quantization
  kOutput,   // how the store is written, not the matrix (never recorded with it)
};

// How the store's .zattrs "params" hold a parameter.
enum class Record {
  kAlways,        // always written; a store without it is refused
  kUnlessAbsent,  // written unless it has its `absent` value, which a store without it
                  // means: parameters added after stores existed, whose older stores and
                  // every store at the old behaviour keep their bytes
  kNever,
};

struct Info {
  std::string_view name;
  std::string_view flag;  // "" = none
  std::string_view help;
  Stage stage;
  Record record = Record::kAlways;
  bool in_request = true;  // a BakeRequest field of the same name
  // Record::kUnlessAbsent: written where this holds, instead of where the
  // value differs from `absent` (a parameter that means something only with
  // another: gather_rays with bounces).
  bool (*recorded_if)(const BakeParams&) = nullptr;
};

// A number in [lo, hi] (a power of two if asked). `special` names the one
// value allowed outside the range and what it means (bits' 0 "auto",
// column_group's 0 "the plan's", bounces' −1 "auto"); `special_is_word`: it is
// spelled so on the command line and in .zattrs, never as its number.
// `unset_is_default`: a request's 0 (proto3's unset) takes the default.
template <class T>
struct Number {
  Info info;
  T BakeParams::*field;
  double lo, hi;
  bool power_of_two = false;
  std::string_view special = {};
  T special_value = 0;
  bool special_is_word = false;
  bool unset_is_default = false;
};

template <class E>
using WordList = std::span<const std::pair<std::string_view, E>>;

// An enum spelled in words (the first is not necessarily the default).
template <class E>
struct Words {
  Info info;
  E BakeParams::*field;
  WordList<E> words;
};

// A bool spelled as two words (`yes`, `no`), or a flag when both are empty.
// `effective` is what is recorded and sent (refine: whether rows are refined).
struct Switch {
  Info info;
  bool BakeParams::*field;
  std::string_view yes = {}, no = {};
  bool absent = false;  // Record::kUnlessAbsent: what a store without it means
  bool (*effective)(const BakeParams&) = nullptr;
};

// A value with its own grammar (the layout, the light domain).
template <class T>
struct Spelled {
  Info info;
  T BakeParams::*field;
  absl::StatusOr<T> (*parse)(std::string_view);
  std::string (*print)(const T&);
};

inline constexpr std::pair<std::string_view, WaveletFilter> kRowFilters[] = {
    {"haar", WaveletFilter::kHaar}, {"daub4", WaveletFilter::kDaub4}};
inline constexpr std::pair<std::string_view, WaveletFilter> kColumnFilters[] = {
    {"haar", WaveletFilter::kHaar},
    {"legall53", WaveletFilter::kLeGall53},
    {"cdf97", WaveletFilter::kCdf97}};
inline constexpr std::pair<std::string_view, ColumnMode> kColumnModes[] = {
    {"adaptive", ColumnMode::kAdaptive}, {"full", ColumnMode::kFull}, {"2d", ColumnMode::k2d}};
inline constexpr std::pair<std::string_view, ErrorScope> kErrorScopes[] = {
    {"matrix", ErrorScope::kMatrix}, {"column", ErrorScope::kColumn}};
inline constexpr std::pair<std::string_view, LevelScaling> kLevelScalings[] = {
    {"uniform", LevelScaling::kUniform}, {"paper", LevelScaling::kPaper}};
inline constexpr std::pair<std::string_view, Transport> kTransports[] = {
    {"diffuse", Transport::kDiffuse}, {"visibility", Transport::kVisibility}};

absl::StatusOr<std::string> ParseLayoutSpelling(std::string_view s);
std::string PrintLayout(const std::string& s);
absl::StatusOr<std::string> ParseText(std::string_view s);  // any string, kept as given
absl::StatusOr<LightDomain> ParseDomainSpelling(std::string_view s);
std::string PrintDomain(const LightDomain& d);
inline bool Refines(const BakeParams& p) { return p.refines(); }
inline bool HasBounces(const BakeParams& p) { return p.bounces != 0; }

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The table: `visit(row)` for every parameter, in the order of --help.
template <class Visit>
void ForEach(Visit&& visit) {
  using S = Stage;
  visit(Number<int>{.info = {"light_res", "--light-res",
                             "cubemap texels per face edge N (power of two, 8..256)", S::kTrace},
                    .field = &BakeParams::light_res,
                    .lo = 8,
                    .hi = 256,
                    .power_of_two = true,
                    .unset_is_default = true});
  visit(Spelled<LightDomain>{
      {"light_domain", "--light-domain",
       "cube | plane:S[:AXIS]: one face of size S (3..10) aligned with a light plane normal to "
       "AXIS (default +Y), for --area-light",
       S::kTrace, Record::kUnlessAbsent},
      &BakeParams::light_domain,
      ParseDomainSpelling,
      PrintDomain});
  visit(Spelled<std::string>{
      {"layout", "--layout",
       "spatial layout: camera[:WxH] | grid | hilbert:WxH | uv[:WxH] | uv1[:WxH] (lightmap "
       "texels of UV channel 0 or 1, default 256x256); uv options after commas: "
       ",fill=zero|push-pull|dilate (texels no chart covers), ,allow-overlap (as "
       "--allow-uv-overlap)",
       S::kTrace},
      &BakeParams::layout,
      ParseLayoutSpelling,
      PrintLayout});
  visit(Number<int>{
      .info = {"supersample", "--supersample", "jittered directions per texel K", S::kTrace},
      .field = &BakeParams::supersample,
      .lo = 1,
      .hi = 256,
      .unset_is_default = true});
  visit(
      Words<WaveletFilter>{{"row_filter", "--row-filter", "row transform: haar | daub4", S::kTrace},
                           &BakeParams::row_filter,
                           kRowFilters});
  visit(Words<ColumnMode>{
      {"column_mode", "--column-mode", "column transform depth: adaptive | full | 2d", S::kColumns},
      &BakeParams::column_mode,
      kColumnModes});
  visit(Words<WaveletFilter>{
      {"column_filter", "--column-filter", "column filter: haar | legall53 | cdf97", S::kColumns},
      &BakeParams::column_filter,
      kColumnFilters});
  visit(
      Number<double>{.info = {"target_error", "--target-error",
                              "relative RMS error budget of the stored columns (DESIGN.md §1, see "
                              "--error-scope)",
                              S::kColumns},
                     .field = &BakeParams::target_error,
                     .lo = 0,
                     .hi = 1,
                     .unset_is_default = true});
  visit(Words<ErrorScope>{
      {"error_scope", "--error-scope",
       "matrix: budget relative to the mean column energy; column: to each column's own",
       S::kColumns},
      &BakeParams::error_scope,
      kErrorScopes});
  visit(Number<int>{
      .info = {"column_terms", "--column-terms",
               "keep exactly K coefficients per column instead of --target-error", S::kColumns},
      .field = &BakeParams::column_terms,
      .lo = 0,
      .hi = std::numeric_limits<int>::max()});
  visit(Number<int>{.info = {"bits", "--bits",
                             "quantization bits 2..16 (each column's max to the largest code), "
                             "or auto (the error budget's quantization half)",
                             S::kColumns},
                    .field = &BakeParams::bits,
                    .lo = 2,
                    .hi = 16,
                    .special = "auto",
                    .special_is_word = true});
  visit(Words<LevelScaling>{{"level_scaling", "--level-scaling",
                             "uniform: one step per column (auto: one matrix-wide step); paper: "
                             "values of level l times 2^l first (4D paper §4.3)",
                             S::kColumns},
                            &BakeParams::level_scaling,
                            kLevelScalings});
  visit(Words<Transport>{{"transport", "--transport",
                          "what a row holds: diffuse (T = V cos/π) or visibility (V alone, for "
                          "glossy relighting by the triple product; needs --row-filter haar)",
                          S::kTrace, Record::kUnlessAbsent},
                         &BakeParams::transport,
                         kTransports});
  visit(Number<uint64_t>{.info = {"seed", "--seed", "job seed (jitter and dither)", S::kTrace},
                         .field = &BakeParams::seed,
                         .lo = 0,
                         .hi = 18446744073709551615.0});
  visit(Switch{{"refine", "--refine",
                "on: trace only where visibility changes (coarse probes, refined along "
                "silhouettes; fully visible texels get their exact integral; cube light domain "
                "only); off: brute force, K rays in every texel",
                S::kTrace, Record::kUnlessAbsent},
               &BakeParams::refine,
               "on",
               "off",
               /*absent=*/false,
               Refines});
  visit(Number<int>{
      .info = {"bounces", "--bounces",
               "diffuse interreflection: light bounced B times off the scene's surfaces, 0..8, "
               "or auto (until the next bounce adds less than half of --target-error); 0: "
               "direct light only. Diffuse transport",
               S::kTrace, Record::kUnlessAbsent},
      .field = &BakeParams::bounces,
      .lo = 0,
      .hi = kMaxBounces,
      .special = "auto",
      .special_value = kAutoBounces,
      .special_is_word = true});
  visit(Number<int>{.info = {"gather_rays", "--gather-rays",
                             "stratified directions per sample that gather each bounce (rounded "
                             "up to a square)",
                             S::kTrace, Record::kUnlessAbsent, true, HasBounces},
                    .field = &BakeParams::gather_rays,
                    .lo = 1,
                    .hi = 4096,
                    .unset_is_default = true});
  visit(Switch{{"keep_staging", "--keep-staging",
                "leave the staging arrays (row-transformed T, transposed) in the store", S::kOutput,
                Record::kNever},
               &BakeParams::keep_staging});
  // An update bake (worker/tiles/row_reuse.h): `wavebake bake --update OLD.wbk
  // [--update-exact]` (flags of bake alone, cli/cmd_bake.cc); not a property
  // of the matrix. The request carries them to the embedded bake's workers.
  visit(Spelled<std::string>{
      {"update_from", "", "the store whose rows an update reuses", S::kOutput, Record::kNever},
      &BakeParams::update_from,
      ParseText,
      PrintLayout});
  visit(Switch{
      {"update_exact", "", "an update reruns the whole column stage", S::kOutput, Record::kNever},
      &BakeParams::update_exact});
  // `wavebake submit --update JOB_OR_STORE` (cli/cmd_submit.cc): the job a
  // coordinator resolves into update_from.
  visit(Spelled<std::string>{{"update_job", "", "the finished job whose store an update reuses",
                              S::kOutput, Record::kNever},
                             &BakeParams::update_job,
                             ParseText,
                             PrintLayout});
  visit(Number<int>{.info = {"tile_size", "--tile-size",
                             "spatial tile edge of one BAKE_TILE task (power of two)", S::kTrace},
                    .field = &BakeParams::tile_size,
                    .lo = 4,
                    .hi = 256,
                    .power_of_two = true,
                    .unset_is_default = true});
  visit(Number<int>{.info = {"column_group", "--column-group",
                             "columns per TRANSFORM_COLUMNS task (0: up to 1024, as many as fit "
                             "256 MiB of column images)",
                             S::kTrace},
                    .field = &BakeParams::column_group,
                    .lo = 1,
                    .hi = 65536,
                    .special = "the plan's"});
  visit(Number<float>{
      .info = {"ray_epsilon", "", "ray offset; 0: 1e-4 × the scene's bounding-box diagonal",
               S::kTrace, Record::kAlways, /*in_request=*/false},
      .field = &BakeParams::ray_epsilon,
      .lo = 0,
      .hi = kInf});
}

// The word a value of `words` is spelled as ("?" if none: a value outside the list).
template <class E>
std::string_view WordOf(WordList<E> words, E value) {
  for (const auto& [w, v] : words)
    if (v == value) return w;
  return "?";
}

}  // namespace wavebake::params
