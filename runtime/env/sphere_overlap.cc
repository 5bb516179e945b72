#include "runtime/env/sphere_overlap.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/util/parallel_for.h"
#include "runtime/env/texel_meridians.h"

namespace wavebake {

namespace {

// 4-point Gauss–Legendre on [−1, 1]: exact for cubics; the integrands are
// smooth on every piece up to the kinks where an interval end crosses a
// pixel row.
constexpr double kNode[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                             0.8611363115940526};
constexpr double kWeight[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                               0.3478548451374538};

// Widest azimuth piece one set of nodes covers (radians, ~2°).
constexpr double kMaxPiece = 0.035;

using Entries = std::vector<std::pair<int, double>>;  // (pixel, area)

struct Grid {
  int width, height;
  std::vector<double> row_mu;  // μ at the top edge of row y, [height + 1]
};

// Adds the pixels of column x that [lo, hi] (in μ) covers, times weight.
void SplitAmongRows(const Grid& g, int x, double lo, double hi, double weight, Entries& out) {
  const int top = std::clamp(static_cast<int>(std::acos(hi) / std::numbers::pi * g.height) - 1, 0,
                             g.height - 1);
  for (int y = top; y < g.height && g.row_mu[y] > lo; ++y) {
    const double overlap = std::min(hi, g.row_mu[y]) - std::max(lo, g.row_mu[y + 1]);
    if (overlap > 0) out.emplace_back(y * g.width + x, weight * overlap);
  }
}

// The root of a monotone f on [l, r], given f(l) and f(r) of opposite signs:
// regula falsi with the Illinois fix, a handful of evaluations to ~1e-15.
template <typename F>
double FindRoot(const F& f, double l, double fl, double r, double fr) {
  double x = 0.5 * (l + r);
  int stuck = 0;  // > 0: l kept twice in a row, < 0: r
  for (int it = 0; it < 60; ++it) {
    x = (l * fr - r * fl) / (fr - fl);
    const double fx = f(x);
    if (fx == 0 || r - l < 1e-15) break;
    if ((fx > 0) == (fr > 0)) {
      r = x, fr = fx;
      if (stuck > 0) fl *= 0.5;
      stuck = stuck > 0 ? stuck + 1 : 1;
    } else {
      l = x, fl = fx;
      if (stuck < 0) fr *= 0.5;
      stuck = stuck < 0 ? stuck - 1 : -1;
    }
    if (std::fabs(fx) < 1e-14) break;
  }
  return x;
}

// Azimuths in (a, b) where an end of the texel's μ-interval crosses a row
// edge: the per-row overlaps have kinks there, which Gauss nodes must not
// straddle. Both ends are monotone on the piece, so each crossing is one root.
void AddRowCrossings(const Grid& g, const TexelMeridians& texel, double a, double b,
                     std::vector<double>& cuts) {
  const double inset = 1e-9 * (b - a);
  const MuInterval at_a = texel.At(a + inset), at_b = texel.At(b - inset);
  if (!(at_a.lo < at_a.hi) || !(at_b.lo < at_b.hi)) return;
  for (bool upper : {false, true}) {
    const double va = upper ? at_a.hi : at_a.lo, vb = upper ? at_b.hi : at_b.lo;
    // Row edges between the two values: μ = row_mu[y] at θ = π y / H.
    const int first = static_cast<int>(std::acos(std::max(va, vb)) / std::numbers::pi * g.height);
    const int last =
        static_cast<int>(std::acos(std::min(va, vb)) / std::numbers::pi * g.height) + 1;
    for (int y = std::max(first, 1); y <= std::min(last, g.height - 1); ++y) {
      const double edge = g.row_mu[y];
      if ((edge - va) * (edge - vb) >= 0) continue;
      auto f = [&](double phi) {
        const MuInterval mu = texel.At(phi);
        return (upper ? mu.hi : mu.lo) - edge;
      };
      cuts.push_back(FindRoot(f, a + inset, va - edge, b - inset, vb - edge));
    }
  }
}

// 4 Gauss nodes on [a, b], all in pixel column x.
void IntegratePiece(const Grid& g, const TexelMeridians& texel, int x, double a, double b,
                    Entries& out) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  for (int k = 0; k < 4; ++k) {
    const MuInterval mu = texel.At(mid + half * kNode[k]);
    if (mu.lo < mu.hi) SplitAmongRows(g, x, mu.lo, mu.hi, half * kWeight[k], out);
  }
}

Entries TexelEntries(const Grid& g, const Cubemap& cube, int m) {
  const TexelMeridians texel(cube, m);
  const std::vector<double>& kinks = texel.breakpoints();
  // Pieces: between kinks and pixel column edges φ = π (2x/W − 1).
  std::vector<double> cuts = kinks;
  const double column = 2 * std::numbers::pi / g.width;
  for (int k = static_cast<int>(std::ceil((kinks.front() + std::numbers::pi) / column));; ++k) {
    const double phi = -std::numbers::pi + k * column;
    if (phi >= kinks.back()) break;
    if (phi > kinks.front()) cuts.push_back(phi);
  }
  std::sort(cuts.begin(), cuts.end());
  Entries entries;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (!(a < b)) continue;
    const int x =
        static_cast<int>(std::floor((0.5 * (a + b) + std::numbers::pi) / column)) % g.width;
    // Pieces no wider than kMaxPiece, for maps whose pixels dwarf the texels.
    const int parts = static_cast<int>(std::ceil((b - a) / kMaxPiece));
    std::vector<double> sub = {a, b};
    for (int k = 1; k < parts; ++k) sub.push_back(a + (b - a) * k / parts);
    for (int k = 0; k < parts; ++k) {
      AddRowCrossings(g, texel, a + (b - a) * k / parts, a + (b - a) * (k + 1) / parts, sub);
    }
    std::sort(sub.begin(), sub.end());
    for (size_t j = 0; j + 1 < sub.size(); ++j)
      IntegratePiece(g, texel, x, sub[j], sub[j + 1], entries);
  }
  // Merge repeats of a pixel (one per node).
  std::sort(entries.begin(), entries.end());
  Entries merged;
  for (const auto& e : entries) {
    if (!merged.empty() && merged.back().first == e.first) {
      merged.back().second += e.second;
    } else {
      merged.push_back(e);
    }
  }
  return merged;
}

}  // namespace

SphereOverlap::SphereOverlap(int width, int height, const Cubemap& cube) {
  Grid grid{width, height, std::vector<double>(height + 1)};
  for (int y = 0; y <= height; ++y) grid.row_mu[y] = std::cos(std::numbers::pi * y / height);
  grid.row_mu[0] = 1, grid.row_mu[height] = -1;
  std::vector<Entries> per_texel(cube.size());
  ParallelFor(cube.size(), [&](int m) { per_texel[m] = TexelEntries(grid, cube, m); });

  first_.assign(1, 0);
  texel_area_.assign(cube.size(), 0);
  pixel_area_.assign(static_cast<size_t>(width) * height, 0);
  for (int m = 0; m < cube.size(); ++m) {
    for (const auto& [p, a] : per_texel[m]) {
      pixel_.push_back(p), area_.push_back(a);
      texel_area_[m] += a, pixel_area_[p] += a;
    }
    first_.push_back(static_cast<int>(pixel_.size()));
  }
}

std::vector<float> SphereOverlap::CubeFromLatLong(std::span<const float> latlong_rgb) const {
  std::vector<float> out(3 * texel_area_.size());
  for (size_t m = 0; m < texel_area_.size(); ++m) {
    double s[3] = {0, 0, 0};
    for (int e = first_[m]; e < first_[m + 1]; ++e) {
      const float* l = &latlong_rgb[3 * size_t(pixel_[e])];
      s[0] += area_[e] * l[0], s[1] += area_[e] * l[1], s[2] += area_[e] * l[2];
    }
    for (int c = 0; c < 3; ++c) out[3 * m + c] = static_cast<float>(s[c] / texel_area_[m]);
  }
  return out;
}

std::vector<float> SphereOverlap::LatLongFromCube(std::span<const float> cube_rgb) const {
  std::vector<double> sum(3 * pixel_area_.size(), 0.0);
  for (size_t m = 0; m < texel_area_.size(); ++m) {
    const float* l = &cube_rgb[3 * m];
    for (int e = first_[m]; e < first_[m + 1]; ++e) {
      double* s = &sum[3 * size_t(pixel_[e])];
      s[0] += area_[e] * l[0], s[1] += area_[e] * l[1], s[2] += area_[e] * l[2];
    }
  }
  std::vector<float> out(sum.size());
  for (size_t i = 0; i < sum.size(); ++i) out[i] = static_cast<float>(sum[i] / pixel_area_[i / 3]);
  return out;
}

}  // namespace wavebake
