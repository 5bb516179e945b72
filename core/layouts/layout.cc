// The `layout` spec: parsing and canonical spelling.
#include "core/layouts/layout.h"

#include <charconv>
#include <limits>
#include <optional>

#include "absl/strings/str_cat.h"
#include "core/bake/bake_params_io.h"
#include "core/util/power_of_two.h"

namespace wavebake {
namespace {

constexpr int kMaxSide = 4096;

std::optional<int> ParseInt(std::string_view s) {
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

// The ",option" tail of a uv spec.
absl::Status ParseUvOptions(std::string_view spec, std::string_view options, LayoutSpec* out) {
  while (!options.empty()) {
    const size_t comma = options.find(',');
    const std::string_view opt = options.substr(0, comma);
    options = comma == std::string_view::npos ? std::string_view() : options.substr(comma + 1);
    if (opt == "allow-overlap") {
      out->allow_uv_overlap = true;
      continue;
    }
    bool known = false;
    for (UncoveredFill f : {UncoveredFill::kZero, UncoveredFill::kPushPull, UncoveredFill::kDilate})
      if (opt == absl::StrCat("fill=", std::string(ToString(f)))) out->fill = f, known = true;
    if (!known)
      return absl::InvalidArgumentError(
          absl::StrCat("layout: '", std::string(spec), "' has an unknown option '",
                       std::string(opt), "' (allow-overlap, fill=zero|push-pull|dilate)"));
  }
  return absl::OkStatus();
}

}  // namespace

std::string_view ToString(UncoveredFill fill) {
  switch (fill) {
    case UncoveredFill::kZero:
      return "zero";
    case UncoveredFill::kPushPull:
      return "push-pull";
    case UncoveredFill::kDilate:
      return "dilate";
  }
  return "?";
}

absl::StatusOr<LayoutSpec> ParseLayout(std::string_view full_spec) {
  // Options follow the first comma (uv layouts only).
  const size_t comma = full_spec.find(',');
  const std::string_view spec = full_spec.substr(0, comma);
  auto bad = [&](const auto&... why) {
    return absl::InvalidArgumentError(
        absl::StrCat("layout: '", std::string(full_spec), "' ", why...));
  };
  const size_t colon = spec.find(':');
  const std::string_view kind = spec.substr(0, colon);
  const bool sized = colon != std::string_view::npos;
  const bool uv = kind == "uv" || kind == "uv1";
  if (comma != std::string_view::npos && !uv) return bad("takes no options after a comma");
  LayoutSpec out;
  if (kind == "grid") {
    if (sized) return bad("takes its size from the grid mesh: write just 'grid'");
    return LayoutSpec{LayoutKind::kGrid, 0, 0};
  } else if (kind == "camera") {
    out.kind = LayoutKind::kCamera;
    if (!sized) return out;  // camera:64x64
  } else if (kind == "hilbert") {
    out.kind = LayoutKind::kHilbert;
    if (!sized) return bad("needs a size, e.g. hilbert:64x64");
  } else if (uv) {
    out = LayoutSpec{LayoutKind::kUv, 256, 256};
    out.uv_channel = kind == "uv1" ? 1 : 0;
    out.fill = kDefaultUvFill;
    if (comma != std::string_view::npos) {
      if (absl::Status s = ParseUvOptions(full_spec, full_spec.substr(comma + 1), &out); !s.ok())
        return s;
    }
    if (!sized) return out;
  } else {
    return bad("is not camera[:WxH] | grid | hilbert:WxH | uv[1][:WxH]");
  }
  const std::string_view size = spec.substr(colon + 1);
  const size_t x = size.find_first_of("xX");
  // INT_MIN stands for "not a number" (an optional here trips GCC 12's
  // -Wmaybe-uninitialized).
  constexpr int kNone = std::numeric_limits<int>::min();
  const int w = ParseInt(size.substr(0, x)).value_or(kNone);
  const int h = x == std::string_view::npos ? kNone : ParseInt(size.substr(x + 1)).value_or(kNone);
  if (w == kNone || h == kNone) return bad("has no size WxH after the colon (e.g. 64x64)");
  for (const auto& [name, v] : {std::pair{"width", w}, std::pair{"height", h}})
    if (!IsPowerOfTwoIn(v, 1, kMaxSide))
      return bad(name, " ", v, " is not a power of two in 1..4096");
  out.width = w;
  out.height = h;
  return out;
}

absl::StatusOr<std::string> WithUvOverlapAllowed(std::string_view layout) {
  absl::StatusOr<LayoutSpec> spec = ParseLayout(layout);
  if (!spec.ok()) return spec.status();
  if (spec->kind != LayoutKind::kUv)
    return absl::InvalidArgumentError(absl::StrCat(
        "allow-uv-overlap: only for uv layouts, the layout is '", std::string(layout), "'"));
  spec->allow_uv_overlap = true;
  return ToString(*spec);
}

std::string ToString(const LayoutSpec& spec) {
  switch (spec.kind) {
    case LayoutKind::kGrid:
      return "grid";
    case LayoutKind::kCamera:
      return absl::StrCat("camera:", spec.width, "x", spec.height);
    case LayoutKind::kHilbert:
      return absl::StrCat("hilbert:", spec.width, "x", spec.height);
    case LayoutKind::kUv:
      return absl::StrCat(spec.uv_channel == 0 ? "uv:" : "uv1:", spec.width, "x", spec.height,
                          spec.allow_uv_overlap ? ",allow-overlap" : "",
                          spec.fill == kDefaultUvFill ? "" : ",fill=",
                          spec.fill == kDefaultUvFill ? "" : std::string(ToString(spec.fill)));
  }
  return "?";
}

}  // namespace wavebake
