#include "core/products/brdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "core/products/ggx.h"

namespace wavebake {
namespace {

// Direction at polar cosine `c` and azimuth `phi` around `axis`.
Vec3 AroundAxis(Vec3 axis, double c, double phi) {
  Vec3 t, b;
  OrthonormalFrame(axis, t, b);
  const double s = std::sqrt(std::max(0.0, 1 - c * c));
  return Normalize(t * static_cast<float>(s * std::cos(phi)) +
                   b * static_cast<float>(s * std::sin(phi)) + axis * static_cast<float>(c));
}

bool Above(Vec3 n, Vec3 w) { return Dot(n, w) > 0; }

// c^e for a whole exponent by squaring (phong:32 is 5 multiplications).
float PowInt(float c, int e) {
  float result = 1;
  for (; e > 0; e >>= 1, c *= c)
    if (e & 1) result *= c;
  return result;
}

double AngleBetween(Vec3 a, Vec3 b) { return std::acos(std::clamp(double{Dot(a, b)}, -1.0, 1.0)); }

// The smallest angle to `axis` of any direction in the cap (centre, radius).
double NearestAngle(Vec3 axis, Vec3 centre, double radius) {
  return std::max(0.0, AngleBetween(axis, centre) - radius);
}

// The half vector of (wi, wo) on n's side, for the half-vector samplers: the
// sampled h maps to wi = Reflect(wo, h), and back by this.
Vec3 HalfVector(Vec3 n, Vec3 wo, Vec3 wi) {
  Vec3 h = wi + wo;
  const float len = Length(h);
  if (!(len > 0)) return n;
  h = h / len;
  return Dot(n, h) < 0 ? -h : h;
}

class Lambert final : public Brdf {
 public:
  double Eval(Vec3 n, Vec3 wo, Vec3 wi) const override {
    return Above(n, wi) && Above(n, wo) ? 1 / std::numbers::pi : 0;
  }
  Vec3 Sample(Vec3 n, Vec3, double u1, double u2) const override {
    return AroundAxis(n, std::sqrt(u1), 2 * std::numbers::pi * u2);  // cosine-weighted
  }
  double Pdf(Vec3 n, Vec3, Vec3 wi) const override {
    return std::max(0.0f, Dot(n, wi)) / std::numbers::pi;
  }
  LobeCone Support(Vec3 n, Vec3, double relative) const override {
    return {n, static_cast<float>(relative)};
  }
  double CapBound(Vec3 n, Vec3, Vec3 centre, double radius) const override {
    return CosineOverCap(n, centre, radius) / std::numbers::pi;
  }
  bool ViewDependent() const override { return false; }
  std::string Name() const override { return "lambert"; }
};

// Normalized Phong: ∫ (E+2)/(2π) cos^E α cos θ dω = 1 at normal incidence.
class Phong final : public Brdf {
 public:
  explicit Phong(double e) : e_(e) {}
  double Eval(Vec3 n, Vec3 wo, Vec3 wi) const override {
    if (!Above(n, wi) || !Above(n, wo)) return 0;
    const double c = Dot(Reflect(wo, n), wi);
    return c > 0 ? (e_ + 2) / (2 * std::numbers::pi) * std::pow(c, e_) : 0;
  }
  Vec3 Sample(Vec3 n, Vec3 wo, double u1, double u2) const override {
    return AroundAxis(Reflect(wo, n), std::pow(u1, 1 / (e_ + 1)), 2 * std::numbers::pi * u2);
  }
  double Pdf(Vec3 n, Vec3 wo, Vec3 wi) const override {
    const double c = Dot(Reflect(wo, n), wi);
    return c > 0 ? (e_ + 1) / (2 * std::numbers::pi) * std::pow(c, e_) : 0;
  }
  LobeCone Support(Vec3 n, Vec3 wo, double relative) const override {
    return {Reflect(wo, n), static_cast<float>(std::pow(relative, 1 / e_))};
  }
  double SumOverDirections(Vec3 n, Vec3 wo, const float* x, const float* y, const float* z,
                           int count) const override {
    if (!Above(n, wo)) return 0;
    const Vec3 r = Reflect(wo, n);
    const float e = static_cast<float>(e_);
    const int whole = e_ == std::floor(e_) && e_ <= 4096 ? static_cast<int>(e_) : -1;
    float sum = 0;
    for (int q = 0; q < count; ++q) {
      const float cn = n.x * x[q] + n.y * y[q] + n.z * z[q];
      const float cr = r.x * x[q] + r.y * y[q] + r.z * z[q];
      if (!(cn > 0 && cr > 0)) continue;
      sum += (whole >= 0 ? PowInt(cr, whole) : std::exp2(e * std::log2(cr))) * cn;
    }
    return (e_ + 2) / (2 * std::numbers::pi) * sum;
  }
  double CapBound(Vec3 n, Vec3 wo, Vec3 centre, double radius) const override {
    const double a = NearestAngle(Reflect(wo, n), centre, radius);
    if (a >= std::numbers::pi / 2) return 0;
    return (e_ + 2) / (2 * std::numbers::pi) * std::pow(std::cos(a), e_) *
           CosineOverCap(n, centre, radius);
  }
  std::string Name() const override { return absl::StrCat("phong:", e_); }

 private:
  double e_;
};

// Half-vector lobe (n·h)^E; h drawn ∝ (n·h)^E (n·h), so pdf(ω_i) =
// (E+1)/(2π) (n·h)^E / (4 |ω_o·h|).
class Blinn final : public Brdf {
 public:
  explicit Blinn(double e)
      : e_(e), k_((e + 2) * (e + 4) / (8 * std::numbers::pi * (std::exp2(-e / 2) + e))) {}
  double Eval(Vec3 n, Vec3 wo, Vec3 wi) const override {
    if (!Above(n, wi) || !Above(n, wo)) return 0;
    return k_ * std::pow(std::max(0.0f, Dot(n, HalfVector(n, wo, wi))), e_);
  }
  Vec3 Sample(Vec3 n, Vec3 wo, double u1, double u2) const override {
    return Reflect(wo, AroundAxis(n, std::pow(u1, 1 / (e_ + 1)), 2 * std::numbers::pi * u2));
  }
  double Pdf(Vec3 n, Vec3 wo, Vec3 wi) const override {
    const Vec3 h = HalfVector(n, wo, wi);
    const double ch = Dot(n, h), oh = std::fabs(Dot(wo, h));
    if (!(ch > 0) || !(oh > 0)) return 0;
    return (e_ + 1) / (2 * std::numbers::pi) * std::pow(ch, e_) / (4 * oh);
  }
  LobeCone Support(Vec3 n, Vec3 wo, double relative) const override {
    // (n·h)^E < relative beyond half-angle β around n; ω_i then leaves the
    // mirror direction by at most 2β.
    const double beta = std::acos(std::clamp(std::pow(relative, 1 / e_), -1.0, 1.0));
    return {Reflect(wo, n), static_cast<float>(std::cos(std::min(std::numbers::pi, 2 * beta)))};
  }
  // A half vector h' off n by β puts ω off the mirror direction by at most
  // 2β (a reflection doubles angles), so n·h ≤ cos(angle(ω, r)/2).
  double CapBound(Vec3 n, Vec3 wo, Vec3 centre, double radius) const override {
    const double half = NearestAngle(Reflect(wo, n), centre, radius) / 2;
    return k_ * std::pow(std::cos(std::min(half, std::numbers::pi / 2)), e_) *
           CosineOverCap(n, centre, radius);
  }
  std::string Name() const override { return absl::StrCat("blinn:", e_); }

 private:
  double e_, k_;
};

// GGX microfacet BRDF with F = 1; h drawn ∝ D(h)(n·h).
class Ggx final : public Brdf {
 public:
  explicit Ggx(double alpha) : a_(alpha) {}
  double Eval(Vec3 n, Vec3 wo, Vec3 wi) const override {
    const double ci = Dot(n, wi), co = Dot(n, wo);
    if (!(ci > 0) || !(co > 0)) return 0;
    const double ch = Dot(n, HalfVector(n, wo, wi));
    return ggx::D(a_, ch) * ggx::G2(a_, ci, co) / (4 * ci * co);
  }
  Vec3 Sample(Vec3 n, Vec3 wo, double u1, double u2) const override {
    const double tan2 = a_ * a_ * u1 / std::max(1e-12, 1 - u1);
    return Reflect(wo, AroundAxis(n, 1 / std::sqrt(1 + tan2), 2 * std::numbers::pi * u2));
  }
  double Pdf(Vec3 n, Vec3 wo, Vec3 wi) const override {
    const Vec3 h = HalfVector(n, wo, wi);
    const double ch = Dot(n, h), oh = std::fabs(Dot(wo, h));
    if (!(ch > 0) || !(oh > 0)) return 0;
    return ggx::D(a_, ch) * ch / (4 * oh);
  }
  LobeCone Support(Vec3 n, Vec3 wo, double relative) const override {
    // D(h)/D(n) = α⁴ / (c²(α²−1)+1)² < relative beyond cos²θ_h = c², and
    // G₂ ≤ 1, so f cos ≤ relative · peak there; ω_i is within 2θ_h of r.
    const double a2 = a_ * a_;
    if (a2 >= 1) return {n, -1};
    const double c2 = (1 - a2 / std::sqrt(relative)) / (1 - a2);
    if (c2 <= 0) return {n, -1};
    const double theta = std::acos(std::sqrt(std::min(1.0, c2)));
    return {Reflect(wo, n), static_cast<float>(std::cos(std::min(std::numbers::pi, 2 * theta)))};
  }
  // f cos θ_i = D G₂ / (4 cos θ_o) ≤ D(θ_h) / (4 cos θ_o), θ_h ≥ angle(ω, r)/2.
  double CapBound(Vec3 n, Vec3 wo, Vec3 centre, double radius) const override {
    const double co = Dot(n, wo);
    if (!(co > 0) || CosineOverCap(n, centre, radius) == 0) return 0;
    const double half = NearestAngle(Reflect(wo, n), centre, radius) / 2;
    return ggx::D(a_, std::cos(std::min(half, std::numbers::pi / 2))) / (4 * co);
  }
  std::string Name() const override { return absl::StrCat("ggx:", a_); }

 private:
  double a_;
};

absl::Status BadBrdf(std::string_view spec, std::string_view why) {
  return absl::InvalidArgumentError(
      absl::StrCat("brdf: '", std::string(spec), "' ", std::string(why),
                   " (lambert | phong:EXP | blinn:EXP | ggx:ROUGHNESS)"));
}

}  // namespace

double CosineOverCap(Vec3 n, Vec3 c, double r) {
  const double alpha = AngleBetween(n, c);
  if (alpha <= r) return 1;
  if (alpha - r >= std::numbers::pi / 2) return 0;
  return std::cos(alpha - r);
}

double Brdf::SumOverDirections(Vec3 n, Vec3 wo, const float* x, const float* y, const float* z,
                               int count) const {
  double sum = 0;
  for (int q = 0; q < count; ++q) {
    const Vec3 w{x[q], y[q], z[q]};
    const float c = Dot(n, w);
    if (c > 0) sum += Eval(n, wo, w) * c;
  }
  return sum;
}

void OrthonormalFrame(Vec3 axis, Vec3& t, Vec3& b) {
  // Duff et al. 2017, "Building an orthonormal basis, revisited".
  const float sign = std::copysign(1.0f, axis.z);
  const float a = -1.0f / (sign + axis.z);
  const float bb = axis.x * axis.y * a;
  t = {1.0f + sign * axis.x * axis.x * a, sign * bb, -sign * axis.x};
  b = {bb, sign + axis.y * axis.y * a, -axis.y};
}

absl::StatusOr<std::unique_ptr<Brdf>> ParseBrdf(std::string_view spec) {
  if (spec == "lambert") return std::make_unique<Lambert>();
  const size_t colon = spec.find(':');
  if (colon == std::string_view::npos) return BadBrdf(spec, "is not a known BRDF");
  const std::string_view kind = spec.substr(0, colon);
  double value = 0;
  if (!absl::SimpleAtod(std::string(spec.substr(colon + 1)), &value) || !std::isfinite(value))
    return BadBrdf(spec, "has a parameter that is not a number");
  if (kind == "phong" || kind == "blinn") {
    if (!(value > 0 && value <= 100000)) return BadBrdf(spec, "needs an exponent in (0, 100000]");
    if (kind == "phong") return std::make_unique<Phong>(value);
    return std::make_unique<Blinn>(value);
  }
  if (kind == "ggx") {
    if (!(value > 0 && value <= 1)) return BadBrdf(spec, "needs a roughness in (0, 1]");
    return std::make_unique<Ggx>(value);
  }
  return BadBrdf(spec, "is not a known BRDF");
}

}  // namespace wavebake
