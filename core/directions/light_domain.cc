#include "core/directions/light_domain.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace wavebake {
namespace {

constexpr const char* kAxisNames[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

absl::Status Bad(const std::string& why) {
  return absl::InvalidArgumentError(absl::StrCat("light_domain: ", why));
}

// Solid angle of the face-plane rectangle [0,x]×[0,y] at unit distance (the
// cube's corner formula, core/directions/cubemap.cc; valid for any signed x, y).
double FaceCornerArea(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1));
}

}  // namespace

std::string ToString(const LightDomain& d) {
  if (!d.is_plane()) return "cube";
  std::string s = absl::StrCat("plane:", d.size);
  if (d.axis != kPosY) absl::StrAppend(&s, ":", kAxisNames[d.axis]);
  return s;
}

absl::Status ValidateLightDomain(const LightDomain& d) {
  if (!d.is_plane()) return absl::OkStatus();
  if (!(d.size >= LightDomain::kMinPlaneSize && d.size <= LightDomain::kMaxPlaneSize))
    return Bad(absl::StrCat("plane size ", d.size, " is outside ", LightDomain::kMinPlaneSize, "..",
                            LightDomain::kMaxPlaneSize, " (a cube face is 2)"));
  if (d.axis < 0 || d.axis > 5) return Bad(absl::StrCat("axis ", d.axis, " is not a cube face"));
  return absl::OkStatus();
}

absl::StatusOr<LightDomain> ParseLightDomain(std::string_view spec) {
  if (spec == "cube") return LightDomain{};
  const std::vector<std::string> parts = absl::StrSplit(std::string(spec), ':');
  if (parts.size() < 2 || parts.size() > 3 || parts[0] != "plane")
    return Bad(absl::StrCat("'", std::string(spec), "' is not cube | plane:S | plane:S:AXIS"));
  LightDomain d;
  d.kind = LightDomain::Kind::kPlane;
  if (!absl::SimpleAtod(parts[1], &d.size) || !std::isfinite(d.size))
    return Bad(absl::StrCat("plane size '", parts[1], "' is not a number"));
  if (parts.size() == 3) {
    std::string axis = parts[2];
    if (!axis.empty() && axis[0] != '+' && axis[0] != '-') axis = "+" + axis;
    const auto* it = std::find(std::begin(kAxisNames), std::end(kAxisNames), axis);
    if (it == std::end(kAxisNames))
      return Bad(absl::StrCat("axis '", parts[2], "' is not one of +X -X +Y -Y +Z -Z"));
    d.axis = static_cast<int>(it - std::begin(kAxisNames));
  }
  if (absl::Status s = ValidateLightDomain(d); !s.ok()) return s;
  // The store records ToString(d): it must read back as the same S.
  double again = 0;
  if (!absl::SimpleAtod(absl::StrCat(d.size), &again) || again != d.size)
    return Bad(absl::StrCat("plane size '", parts[1], "' has more than 6 significant digits"));
  return d;
}

FaceFrame FaceFrameOf(int face) {
  switch (face) {
    case kPosX:
      return {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}};
    case kNegX:
      return {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
    case kPosY:
      return {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
    case kNegY:
      return {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}};
    case kPosZ:
      return {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}};
    default:
      return {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}};
  }
}

PlaneFace::PlaneFace(int n, double size, int axis)
    : n_(n), size_(size), axis_(axis), frame_(FaceFrameOf(axis)) {}

Vec3 PlaneFace::Direction(double s, double t) const {
  const float u = static_cast<float>(size_ * (s - 0.5)), v = static_cast<float>(size_ * (t - 0.5));
  return Normalize(frame_.major + frame_.s_axis * u + frame_.t_axis * v);
}

Vec3 PlaneFace::TexelCenter(int m) const {
  return Direction((m % n_ + 0.5) / n_, (m / n_ + 0.5) / n_);
}

double PlaneFace::SolidAngle(int m) const {
  const int x = m % n_, y = m / n_;
  const double x0 = size_ * (double(x) / n_ - 0.5), x1 = size_ * (double(x + 1) / n_ - 0.5);
  const double y0 = size_ * (double(y) / n_ - 0.5), y1 = size_ * (double(y + 1) / n_ - 0.5);
  return FaceCornerArea(x1, y1) - FaceCornerArea(x0, y1) - FaceCornerArea(x1, y0) +
         FaceCornerArea(x0, y0);
}

double PlaneFace::TotalSolidAngle() const {
  const double h = size_ / 2;
  return 4 * FaceCornerArea(h, h);
}

int PlaneFace::Lookup(Vec3 d) const {
  const double c = Dot(d, frame_.major);
  if (!(c > 0)) return -1;
  const double s = Dot(d, frame_.s_axis) / (c * size_) + 0.5;
  const double t = Dot(d, frame_.t_axis) / (c * size_) + 0.5;
  if (!(s >= 0 && s <= 1 && t >= 0 && t <= 1)) return -1;
  const int x = std::clamp(static_cast<int>(s * n_), 0, n_ - 1);
  const int y = std::clamp(static_cast<int>(t * n_), 0, n_ - 1);
  return y * n_ + x;
}

}  // namespace wavebake
