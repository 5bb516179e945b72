#include "runtime/env/texel_meridians.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace wavebake {

namespace {

// Side faces (±X, ±Z) as core/directions/cubemap.cc builds them: d = axis + sc·right −
// tc·ŷ, so sc depends on φ only and tc = −y / (d·axis).
struct SideFrame {
  Vec3 axis, right;
};
SideFrame SideFrameOf(int face) {
  switch (face) {
    case kPosX:
      return {{1, 0, 0}, {0, 0, -1}};
    case kNegX:
      return {{-1, 0, 0}, {0, 0, 1}};
    case kPosZ:
      return {{0, 0, 1}, {1, 0, 0}};
    default:
      return {{0, 0, -1}, {-1, 0, 0}};
  }
}

double Azimuth(double x, double z) { return std::atan2(x, -z); }

// μ of a direction whose cot θ is u.
double MuOfCot(double u) { return u / std::sqrt(1 + u * u); }

// On the +Y face (sc, tc) = tan θ · (sin φ, −cos φ); on −Y, tan(π − θ) ·
// (sin φ, cos φ).
double CapTcSign(int face) { return face == kPosY ? -1 : 1; }

}  // namespace

TexelMeridians::TexelMeridians(const Cubemap& cube, int m) {
  const Texel t = cube.TexelOf(m);
  const int n = cube.n();
  face_ = t.face;
  s0_ = 2.0 * t.x / n - 1, s1_ = 2.0 * (t.x + 1) / n - 1;
  t0_ = 2.0 * t.y / n - 1, t1_ = 2.0 * (t.y + 1) / n - 1;
  if (face_ == kPosY || face_ == kNegY) {
    InitCap();
  } else {
    InitSide();
  }
}

void TexelMeridians::InitSide() {
  const SideFrame f = SideFrameOf(face_);
  double a = Azimuth(f.axis.x + s0_ * f.right.x, f.axis.z + s0_ * f.right.z);
  double b = Azimuth(f.axis.x + s1_ * f.right.x, f.axis.z + s1_ * f.right.z);
  if (a > b) std::swap(a, b);
  if (b - a > std::numbers::pi)
    std::swap(a, b), b += 2 * std::numbers::pi;  // the texel straddles the seam
  breaks_ = {a, b};
  // At(φ) peaks where φ faces the axis; keep the pieces monotone.
  double facing = Azimuth(f.axis.x, f.axis.z);
  facing = a + std::remainder(facing - a, 2 * std::numbers::pi);
  if (a < facing && facing < b) breaks_.insert(breaks_.begin() + 1, facing);
}

void TexelMeridians::InitCap() {
  // With the pole inside (N = 1) the texel spans every azimuth; otherwise it
  // subtends at most π from the pole, and its corners' azimuths, unwrapped
  // around the first one, bound it.
  const bool pole_inside = s0_ < 0 && 0 < s1_ && t0_ < 0 && 0 < t1_;
  breaks_.clear();
  if (pole_inside) breaks_ = {-std::numbers::pi, std::numbers::pi};
  for (double s : {s0_, s1_}) {
    for (double t : {t0_, t1_}) {
      if (s == 0 && t == 0) continue;  // the pole itself has no azimuth
      double phi = std::atan2(s, CapTcSign(face_) * t);
      if (!pole_inside && !breaks_.empty()) {
        phi = breaks_[0] + std::remainder(phi - breaks_[0], 2 * std::numbers::pi);
      }
      breaks_.push_back(phi);
    }
  }
  std::sort(breaks_.begin(), breaks_.end());
  // Between corners one edge of the rectangle bounds each end of the ray,
  // r = edge / sin φ or edge / cos φ: monotone within a quadrant.
  const double lo = breaks_.front(), hi = breaks_.back();
  for (int q = static_cast<int>(std::floor(lo / (std::numbers::pi / 2))) + 1;
       q * (std::numbers::pi / 2) < hi; ++q) {
    breaks_.push_back(q * (std::numbers::pi / 2));
  }
  std::sort(breaks_.begin(), breaks_.end());
}

MuInterval TexelMeridians::At(double phi) const {
  const double sp = std::sin(phi), cp = std::cos(phi);
  if (face_ != kPosY && face_ != kNegY) {
    const SideFrame f = SideFrameOf(face_);
    const double c = sp * f.axis.x - cp * f.axis.z;  // horizontal direction · axis
    if (c <= 0) return {};
    return {MuOfCot(-t1_ * c), MuOfCot(-t0_ * c)};
  }
  // The ray r · e, r ≥ 0, clipped to the rectangle (slab method).
  const double e[2] = {sp, CapTcSign(face_) * cp};
  const double lo[2] = {s0_, t0_}, hi[2] = {s1_, t1_};
  double ra = 0, rb = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 2; ++i) {
    if (e[i] == 0) {
      if (lo[i] > 0 || hi[i] < 0) return {};
      continue;
    }
    const double u = lo[i] / e[i], v = hi[i] / e[i];
    ra = std::max(ra, std::min(u, v)), rb = std::min(rb, std::max(u, v));
  }
  if (ra >= rb) return {};
  // |μ| = 1 / √(1 + r²): largest at the pole (r = 0).
  const double near = 1 / std::sqrt(1 + ra * ra), far = 1 / std::sqrt(1 + rb * rb);
  return face_ == kPosY ? MuInterval{far, near} : MuInterval{-near, -far};
}

}  // namespace wavebake
