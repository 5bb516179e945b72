// The `layout` spec: parsing and canonical spelling.
#include "core/layout.h"

#include <charconv>
#include <optional>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

constexpr int kMaxSide = 4096;

bool IsPow2(int v) { return v > 0 && (v & (v - 1)) == 0; }

std::optional<int> ParseInt(std::string_view s) {
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

absl::StatusOr<LayoutSpec> ParseLayout(std::string_view spec) {
  auto bad = [&](const auto&... why) {
    return absl::InvalidArgumentError(absl::StrCat("layout: '", std::string(spec), "' ", why...));
  };
  const size_t colon = spec.find(':');
  const std::string_view kind = spec.substr(0, colon);
  const bool sized = colon != std::string_view::npos;
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
  } else {
    return bad("is not camera[:WxH] | grid | hilbert:WxH");
  }
  const std::string_view size = spec.substr(colon + 1);
  const size_t x = size.find_first_of("xX");
  const std::optional<int> w = ParseInt(size.substr(0, x));
  const std::optional<int> h =
      x == std::string_view::npos ? std::nullopt : ParseInt(size.substr(x + 1));
  if (!w || !h) return bad("has no size WxH after the colon (e.g. 64x64)");
  for (const auto& [name, v] : {std::pair{"width", *w}, std::pair{"height", *h}})
    if (!IsPow2(v) || v > kMaxSide) return bad(name, " ", v, " is not a power of two in 1..4096");
  out.width = *w;
  out.height = *h;
  return out;
}

std::string ToString(const LayoutSpec& spec) {
  switch (spec.kind) {
    case LayoutKind::kGrid:
      return "grid";
    case LayoutKind::kCamera:
      return absl::StrCat("camera:", spec.width, "x", spec.height);
    case LayoutKind::kHilbert:
      return absl::StrCat("hilbert:", spec.width, "x", spec.height);
  }
  return "?";
}

}  // namespace wavebake
