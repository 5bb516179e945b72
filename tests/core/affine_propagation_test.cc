#include "core/products/affine_propagation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// N × [the length of [x/N, (x+1)/N] inside the preimage of source texel q]:
// the weight of source texel q in the mean of target texel x under q = s v + o.
double Weight(int x, int n, int q, int r, double s, double o) {
  const double a = std::max(double(x) / n, (double(q) / r - o) / s);
  const double b = std::min(double(x + 1) / n, (double(q + 1) / r - o) / s);
  return std::max(0.0, b - a) * n;
}

// The oracle in the pixel domain: every target texel the exact mean of the
// piecewise-constant source over its footprint (0 outside the source), then
// the row transform. Channel-major planes [3][n*n].
std::vector<float> ResampleAndTransform(const std::vector<float>& source, int r, int n,
                                        const AffineMap2d& m) {
  std::vector<float> out(3 * n * n, 0.0f);
  for (int c = 0; c < 3; ++c) {
    std::span<float> plane(out.data() + c * n * n, n * n);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        double sum = 0;
        for (int qy = 0; qy < r; ++qy) {
          const double wy = Weight(y, n, qy, r, m.s_y, m.o_y);
          if (wy == 0) continue;
          for (int qx = 0; qx < r; ++qx)
            sum += wy * Weight(x, n, qx, r, m.s_x, m.o_x) * source[c * r * r + qy * r + qx];
        }
        plane[y * n + x] = static_cast<float>(sum);
      }
    }
    Forward2d(WaveletFilter::kHaar, plane, n, n, MaxDepth(n, n));
  }
  return out;
}

struct Light {
  std::vector<float> pixels;  // [3][r*r]
  std::vector<SourceTerm> terms;
};

Light RandomLight(int r, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  Light l;
  l.pixels.resize(3 * r * r);
  for (float& v : l.pixels) v = u(rng);
  std::vector<float> coeffs = l.pixels;
  for (int c = 0; c < 3; ++c)
    Forward2d(WaveletFilter::kHaar, std::span(coeffs).subspan(c * r * r, r * r), r, r,
              MaxDepth(r, r));
  for (int i = 0; i < r * r; ++i)
    l.terms.push_back({static_cast<uint16_t>(i % r),
                       static_cast<uint16_t>(i / r),
                       {coeffs[i], coeffs[r * r + i], coeffs[2 * r * r + i]}});
  return l;
}

std::vector<uint16_t> AllTargets(int n) {
  std::vector<uint16_t> t(n * n);
  for (int i = 0; i < n * n; ++i) t[i] = static_cast<uint16_t>(i);
  return t;
}

double MaxAbs(const std::vector<float>& v) {
  double m = 0;
  for (float x : v) m = std::max(m, double(std::fabs(x)));
  return m;
}

// Eq. 30 in two steps against resampling the light in the pixel domain, for
// maps that magnify, shrink, shift the light partly or wholly off the face.
TEST(AffinePropagation, MatchesResamplingTheLightInThePixelDomain) {
  const int r = 16;
  const Light light = RandomLight(r, 11);
  const std::vector<AffineMap2d> maps = {{1, 0, 1, 0},           {0.6, 0.2, 0.6, -0.1},
                                         {2.5, -0.7, 1.3, -0.4}, {0.3, 0.35, 4, -3.2},
                                         {1.7, -0.9, 0.45, 0.5}, {3, 2, 1, 0}};  // the last misses
  for (int n : {8, 16, 32}) {
    AffinePropagator propagator(light.terms, r, n);
    const std::vector<uint16_t> targets = AllTargets(n);
    for (const AffineMap2d& m : maps) {
      const std::vector<float> oracle = ResampleAndTransform(light.pixels, r, n, m);
      std::vector<float> rgb(3 * n * n);
      propagator.Propagate(m, targets, rgb);
      const double tol = 2e-5 * std::max(1.0, MaxAbs(oracle));
      for (int k = 0; k < n * n; ++k)
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(rgb[3 * k + c], oracle[c * n * n + k], tol)
              << "n " << n << " target " << k << " map s_x " << m.s_x << " o_x " << m.o_x;
    }
  }
}

// Propagation is linear in the sources, and a subset of targets gets the
// same values as the whole face (the target-level truncation of §5.3.3
// changes which coefficients are computed, not their values).
TEST(AffinePropagation, SubsetsOfSourcesAndTargetsAreConsistent) {
  const int r = 16, n = 16;
  const Light light = RandomLight(r, 5);
  const AffineMap2d m{0.8, 0.05, 1.4, -0.3};
  std::vector<SourceTerm> first(light.terms.begin(), light.terms.begin() + 40);
  std::vector<SourceTerm> rest(light.terms.begin() + 40, light.terms.end());
  AffinePropagator all(light.terms, r, n), a(first, r, n), b(rest, r, n);
  const std::vector<uint16_t> targets = AllTargets(n);
  std::vector<float> l_all(3 * n * n), l_a(3 * n * n), l_b(3 * n * n);
  all.Propagate(m, targets, l_all);
  a.Propagate(m, targets, l_a);
  b.Propagate(m, targets, l_b);
  for (int i = 0; i < 3 * n * n; ++i) ASSERT_NEAR(l_all[i], l_a[i] + l_b[i], 1e-4);

  const std::vector<uint16_t> some = {0, 3, 17, 100, 255, 64};
  std::vector<float> l_some(3 * some.size());
  all.Propagate(m, some, l_some);
  for (size_t j = 0; j < some.size(); ++j)
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(l_some[3 * j + c], l_all[3 * some[j] + c]);
}

// The memory-based table returns the computed couplings at its grid points,
// and a nearby map's couplings elsewhere: the error shrinks as the grid
// gets finer (slowly, for a light of independent random texels, where every
// texel edge moves with the snapped scale and offset).
TEST(AffinePropagation, TabulatedCouplingsAgreeAtGridPointsAndConvergeBetween) {
  const int r = 8, n = 8;
  const Light light = RandomLight(r, 9);
  CouplingTableOptions coarse{
      .source_res = r, .target_res = n, .s_min = 0.25, .s_max = 4, .scales = 9, .offsets = 64};
  absl::StatusOr<CouplingTable> table = CouplingTable::Build(coarse);
  ASSERT_TRUE(table.ok()) << table.status();
  // A grid point: scale 4 of 9 is s = 1, offset i is −s + (1 + s)(i + ½)/64.
  const double s = 1, o = -1 + 2 * (40 + 0.5) / 64;
  const AffineMap2d on_grid{s, o, s, o};
  AffinePropagator computed(light.terms, r, n), tabulated(light.terms, r, n, &*table);
  const std::vector<uint16_t> targets = AllTargets(n);
  std::vector<float> exact(3 * n * n), looked_up(3 * n * n);
  computed.Propagate(on_grid, targets, exact);
  tabulated.Propagate(on_grid, targets, looked_up);
  for (int i = 0; i < 3 * n * n; ++i) ASSERT_NEAR(looked_up[i], exact[i], 1e-5);

  const AffineMap2d off_grid{1.13, -0.21, 0.87, 0.33};
  computed.Propagate(off_grid, targets, exact);
  double previous = 1e30;
  for (int refine : {1, 4, 16}) {
    CouplingTableOptions o2 = coarse;
    o2.scales = 8 * refine + 1;
    o2.offsets = 64 * refine;
    absl::StatusOr<CouplingTable> t2 = CouplingTable::Build(o2);
    ASSERT_TRUE(t2.ok());
    AffinePropagator p(light.terms, r, n, &*t2);
    p.Propagate(off_grid, targets, looked_up);
    double err = 0, norm = 0;
    for (int i = 0; i < 3 * n * n; ++i) {
      err += (looked_up[i] - exact[i]) * (looked_up[i] - exact[i]);
      norm += exact[i] * exact[i];
    }
    const double rel = std::sqrt(err / norm);
    EXPECT_LT(rel, previous) << "refine " << refine;
    previous = rel;
  }
  EXPECT_LT(previous, 0.1);
}

}  // namespace
}  // namespace wavebake
