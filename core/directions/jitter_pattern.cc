#include "core/directions/jitter_pattern.h"

#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

constexpr int kMaxSupersample = 256;
// Keeps the jitter stream apart from any other stream derived from the job
// seed (the quantization dither uses job seed ⊕ column, DESIGN.md §1).
constexpr uint64_t kJitterDomain = 0x6a69747465722d31ull;  // "jitter-1"

// SplitMix64 (Steele, Lea, Flood 2014): a bijective 64-bit mixer, and a
// counter-based generator on top of it. Integer-only, so the pattern is the
// same on every worker and compiler.
uint64_t Mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t Next() { return Mix64(state_ += 0x9e3779b97f4a7c15ull); }
  // Uniform in the open interval (0, 1) on a 2^-24 grid: never exactly on a
  // stratum edge, where a direction would sit on the border of two texels.
  double NextOpen01() { return (static_cast<double>(Next() >> 40) + 0.5) * 0x1p-24; }

 private:
  uint64_t state_;
};

// hash(job seed, texel): the only input of a texel's jitter (DESIGN.md §1).
uint64_t TexelSeed(uint64_t job_seed, int texel) {
  return Mix64(Mix64(job_seed ^ kJitterDomain) + static_cast<uint64_t>(texel));
}

// Texel (tx, ty) with index m of an N-texel face whose unit direction
// through face coordinates (s, t) is dir(s, t): K stratified jittered
// directions, its 4 corners and its solid angle.
template <typename Dir>
void AddTexel(int n_texels, int tx, int ty, int m, uint64_t seed, const Dir& dir,
              double solid_angle, JitterPattern& p) {
  const double n = n_texels, k = p.strata;
  SplitMix64 rng(TexelSeed(seed, m));
  for (int j = 0; j < p.strata; ++j) {
    for (int i = 0; i < p.strata; ++i) {
      const double u = rng.NextOpen01(), v = rng.NextOpen01();
      const Vec3 d = dir((tx + (i + u) / k) / n, (ty + (j + v) / k) / n);
      p.x.push_back(d.x);
      p.y.push_back(d.y);
      p.z.push_back(d.z);
    }
  }
  const double s0 = tx / n, s1 = (tx + 1) / n, t0 = ty / n, t1 = (ty + 1) / n;
  for (auto [s, t] : {std::pair{s0, t0}, {s1, t0}, {s1, t1}, {s0, t1}}) {
    p.corners.push_back(dir(s, t));
  }
  p.solid_angle.push_back(static_cast<float>(solid_angle));
}

absl::StatusOr<JitterPattern> EmptyPattern(int n, int texels, int supersample) {
  if (supersample < 1 || supersample > kMaxSupersample) {
    return absl::InvalidArgumentError(
        absl::StrCat("supersample ", supersample, " is not in [1, ", kMaxSupersample, "]"));
  }
  if (n < 1) return absl::InvalidArgumentError(absl::StrCat("light resolution ", n, " < 1"));
  JitterPattern p;
  p.n = n;
  p.strata = 1;
  while (p.strata * p.strata < supersample) ++p.strata;  // K rounded up to a square
  p.per_texel = p.strata * p.strata;
  const size_t rays = static_cast<size_t>(texels) * p.per_texel;
  p.x.reserve(rays);
  p.y.reserve(rays);
  p.z.reserve(rays);
  p.corners.reserve(static_cast<size_t>(texels) * 4);
  p.solid_angle.reserve(texels);
  return p;
}

}  // namespace

absl::StatusOr<JitterPattern> MakeJitterPattern(const Cubemap& cubemap, int supersample,
                                                uint64_t seed) {
  absl::StatusOr<JitterPattern> p = EmptyPattern(cubemap.n(), cubemap.size(), supersample);
  if (!p.ok()) return p.status();
  for (int m = 0; m < cubemap.size(); ++m) {
    const Texel tex = cubemap.TexelOf(m);
    const auto dir = [&](double s, double t) { return Cubemap::FaceDirection(tex.face, s, t); };
    AddTexel(cubemap.n(), tex.x, tex.y, m, seed, dir, cubemap.SolidAngle(m), *p);
  }
  return p;
}

absl::StatusOr<JitterPattern> MakeJitterPattern(const PlaneFace& face, int supersample,
                                                uint64_t seed) {
  absl::StatusOr<JitterPattern> p = EmptyPattern(face.n(), face.texels(), supersample);
  if (!p.ok()) return p.status();
  const auto dir = [&](double s, double t) { return face.Direction(s, t); };
  for (int m = 0; m < face.texels(); ++m) {
    AddTexel(face.n(), m % face.n(), m / face.n(), m, seed, dir, face.SolidAngle(m), *p);
  }
  return p;
}

}  // namespace wavebake
