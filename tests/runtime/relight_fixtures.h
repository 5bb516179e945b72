#pragma once
// Fixtures of the relighting tests, built without the code under test:
// random compressed columns, random sample grids, and a "mini bake" that
// traces a real transport matrix of a built-in scene with the bake's own
// row kernel (core/transport/transport_row.h) and compresses its columns in-test
// (adaptive depth + energy budget, DESIGN.md §1), so the runtime can be
// checked against the dense matrix it came from.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "core/bake/bake_params.h"
#include "core/columns/compressed_columns.h"
#include "core/columns/nla.h"
#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/layouts/layout.h"
#include "core/layouts/sample_layout.h"
#include "core/layouts/samples.h"
#include "core/transport/ray_caster.h"
#include "core/transport/transport_row.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/scene_files/scene_loader.h"

namespace wavebake::testing {

// Columns with `nnz` random positions each (distinct), values in [−1, 1],
// depth uniform in [0, MaxDepth(W, H)]: arbitrary transform-domain data.
inline CompressedColumns RandomColumns(int width, int height, int light_res, WaveletFilter filter,
                                       int nnz, uint32_t seed) {
  std::mt19937 rng(seed);
  CompressedColumns t;
  t.width = width;
  t.height = height;
  t.light_res = light_res;
  t.columns = 6 * light_res * light_res;
  t.column_filter = filter;
  t.indptr.push_back(0);
  std::vector<uint32_t> cells(static_cast<size_t>(width) * height);
  for (size_t i = 0; i < cells.size(); ++i) cells[i] = static_cast<uint32_t>(i);
  std::uniform_real_distribution<float> value(-1, 1);
  std::uniform_int_distribution<int> depth(0, MaxDepth(width, height));
  for (int m = 0; m < t.columns; ++m) {
    std::shuffle(cells.begin(), cells.end(), rng);
    std::vector<uint32_t> pos(cells.begin(), cells.begin() + std::min<size_t>(nnz, cells.size()));
    std::sort(pos.begin(), pos.end());
    for (uint32_t p : pos) {
      t.indices.push_back(p);
      t.values.push_back(value(rng));
    }
    t.indptr.push_back(static_cast<int64_t>(t.indices.size()));
    t.depth.push_back(static_cast<uint8_t>(depth(rng)));
  }
  return t;
}

// A W×H grid with about `masked` of its cells empty; albedo in [0.2, 1].
inline SampleSet RandomSamples(int width, int height, double masked, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  SampleSet s;
  s.width = width;
  s.height = height;
  for (int i = 0; i < width * height; ++i) {
    if (u(rng) < masked) {
      s.grid.push_back(-1);
      continue;
    }
    s.grid.push_back(s.size());
    s.position.push_back({u(rng), u(rng), 0});
    s.normal.push_back({0, 0, 1});
    s.albedo.push_back({0.2f + 0.8f * u(rng), 0.2f + 0.8f * u(rng), 0.2f + 0.8f * u(rng)});
  }
  return s;
}

// Relative RMS and max abs difference over finite entries of `ref`.
struct Diff {
  double rel_rms = 0, max_abs = 0;
};
inline Diff Compare(const std::vector<float>& got, const std::vector<float>& ref) {
  double num = 0, den = 0, max_abs = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    if (std::isnan(ref[i])) continue;
    const double d = double{got[i]} - ref[i];
    num += d * d;
    den += double{ref[i]} * ref[i];
    max_abs = std::max(max_abs, std::fabs(d));
  }
  return {den > 0 ? std::sqrt(num / den) : std::sqrt(num), max_abs};
}

struct MiniBakeOptions {
  std::string scene = "builtin:disk-over-plane";
  int width = 32, height = 32;  // camera layout
  int light_res = 8;
  int supersample = 4;
  uint64_t seed = 1;
  WaveletFilter column_filter = WaveletFilter::kHaar;
  double target_error = 0.01;                 // ≤ 0: keep every nonzero coefficient
  Transport transport = Transport::kDiffuse;  // kVisibility: rows of V (VisibilityRow)
};

struct MiniBake {
  SampleSet samples;
  int columns = 0;
  // Uncompressed T by grid cell, pixel basis (cube texels): [cells][M];
  // masked cells are all zero.
  std::vector<float> pixel_rows;
  // The same rows after the per-face full-depth row transform (Forward2d,
  // Haar), the basis the columns are stored in.
  std::vector<float> wavelet_rows;
  CompressedColumns compressed;
};

// Column m of `rows` ([cells][M]) as an image over the grid.
inline std::vector<float> ColumnImage(const std::vector<float>& rows, int cells, int columns,
                                      int m) {
  std::vector<float> img(cells);
  for (int i = 0; i < cells; ++i) img[i] = rows[static_cast<size_t>(i) * columns + m];
  return img;
}

// DESIGN.md §1 "Column transform" / "Coefficient selection", independently:
// every depth is tried, the one needing the fewest coefficients under the
// absolute budget target² · mean column energy wins (ties: shallower).
inline void CompressColumns(MiniBake& b, const MiniBakeOptions& o) {
  const int w = b.samples.width, h = b.samples.height, cells = w * h, cols = b.columns;
  double energy = 0;
  for (float v : b.wavelet_rows) energy += double{v} * v;
  const double budget = o.target_error > 0 ? o.target_error * o.target_error * energy / cols : -1.0;
  CompressedColumns& t = b.compressed;
  t = CompressedColumns{};
  t.width = w;
  t.height = h;
  t.light_res = o.light_res;
  t.columns = cols;
  t.column_filter = o.column_filter;
  t.indptr.push_back(0);
  for (int m = 0; m < cols; ++m) {
    const std::vector<float> pixels = ColumnImage(b.wavelet_rows, cells, cols, m);
    int best_depth = 0, best_count = cells + 1;
    for (int d = 0; d <= MaxDepth(w, h); ++d) {
      std::vector<float> img = pixels;
      Forward2d(o.column_filter, img, w, h, d);
      const int count = CountForBudget(img, SynthesisNormsRef(o.column_filter, w, h, d), budget);
      if (count < best_count) best_count = count, best_depth = d;
    }
    std::vector<float> img = pixels;
    Forward2d(o.column_filter, img, w, h, best_depth);
    const Selection sel =
        SelectForBudget(img, SynthesisNormsRef(o.column_filter, w, h, best_depth), budget);
    for (uint32_t p : sel.kept) {
      t.indices.push_back(p);
      t.values.push_back(img[p]);
    }
    t.indptr.push_back(static_cast<int64_t>(t.indices.size()));
    t.depth.push_back(static_cast<uint8_t>(best_depth));
  }
}

inline MiniBake RunMiniBake(const MiniBakeOptions& o) {
  MiniBake b;
  auto scene = LoadScene(o.scene);
  if (!scene.ok()) throw std::runtime_error(std::string(scene.status().message()));
  auto caster = RayCaster::Build(*scene);
  if (!caster.ok()) throw std::runtime_error(std::string(caster.status().message()));
  auto samples = MakeSampleSet(*scene, *caster, LayoutSpec{LayoutKind::kCamera, o.width, o.height});
  if (!samples.ok()) throw std::runtime_error(std::string(samples.status().message()));
  b.samples = *std::move(samples);
  const Cubemap cube(o.light_res);
  auto jitter = MakeJitterPattern(cube, o.supersample, o.seed);
  if (!jitter.ok()) throw std::runtime_error(std::string(jitter.status().message()));
  b.columns = cube.size();
  const int cells = b.samples.cells(), n = o.light_res;
  b.pixel_rows.assign(static_cast<size_t>(cells) * b.columns, 0.0f);
  for (int cell = 0; cell < cells; ++cell) {
    const int32_t id = b.samples.grid[cell];
    if (id < 0) continue;
    const std::span<float> row(b.pixel_rows.data() + static_cast<size_t>(cell) * b.columns,
                               b.columns);
    if (o.transport == Transport::kVisibility)
      VisibilityRow(*caster, cube, *jitter, b.samples.position[id], b.samples.normal[id],
                    caster->DefaultEpsilon(), row, nullptr);
    else
      TransportRow(*caster, cube, *jitter, b.samples.position[id], b.samples.normal[id],
                   caster->DefaultEpsilon(), row, nullptr);
  }
  b.wavelet_rows = b.pixel_rows;
  for (int cell = 0; cell < cells; ++cell) {
    for (int face = 0; face < 6; ++face) {
      float* f = b.wavelet_rows.data() + static_cast<size_t>(cell) * b.columns + face * n * n;
      Forward2d(WaveletFilter::kHaar, std::span<float>(f, n * n), n, n, MaxDepth(n, n));
    }
  }
  CompressColumns(b, o);
  return b;
}

// A bake shared by the tests of one binary (gtest runs them in turn), made
// on first use: scenes with several sharp shadows are worth baking once.
inline const MiniBake& SharedBake(const MiniBakeOptions& o) {
  static std::map<std::tuple<std::string, int, Transport, double>, MiniBake> bakes;
  const auto key = std::make_tuple(o.scene, o.light_res, o.transport, o.target_error);
  auto it = bakes.find(key);
  if (it == bakes.end()) it = bakes.emplace(key, RunMiniBake(o)).first;
  return it->second;
}

// B = Σ_m T[s,m] L[m] in double from the pixel-basis rows, × albedo, NaN
// where masked: the dense reference the tests compare relighting against.
// cube_rgb: texel radiance [3M].
inline std::vector<float> DenseFromRows(const MiniBake& b, const std::vector<float>& cube_rgb) {
  const int cells = b.samples.cells();
  std::vector<float> out(3 * static_cast<size_t>(cells), std::nanf(""));
  for (int cell = 0; cell < cells; ++cell) {
    const int32_t id = b.samples.grid[cell];
    if (id < 0) continue;
    double sum[3] = {0, 0, 0};
    for (int m = 0; m < b.columns; ++m) {
      const double t = b.pixel_rows[static_cast<size_t>(cell) * b.columns + m];
      for (int c = 0; c < 3; ++c) sum[c] += t * cube_rgb[3 * m + c];
    }
    const Vec3 a = b.samples.albedo[id];
    out[3 * cell] = static_cast<float>(sum[0] * a.x);
    out[3 * cell + 1] = static_cast<float>(sum[1] * a.y);
    out[3 * cell + 2] = static_cast<float>(sum[2] * a.z);
  }
  return out;
}

// A sharp, bright "sun" lobe rotating about +Y over a smooth sky gradient,
// point-sampled at texel centres: lighting with both a very high and a
// very low frequency part. degrees: the sun's azimuth.
inline std::vector<float> SunAndSky(int light_res, double degrees, double sun_width = 0.15) {
  const Cubemap cube(light_res);
  const double a = degrees * std::numbers::pi / 180;
  const Vec3 sun =
      Normalize(Vec3{static_cast<float>(std::cos(a)), 0.8f, static_cast<float>(std::sin(a))});
  std::vector<float> rgb(3 * static_cast<size_t>(cube.size()));
  for (int m = 0; m < cube.size(); ++m) {
    const Vec3 d = cube.TexelCenter(m);
    const double sky = 0.3 + 0.3 * std::max(0.0f, d.y);
    const double lobe = 20 * std::exp((Dot(d, sun) - 1) / (sun_width * sun_width));
    rgb[3 * m] = static_cast<float>(sky * 0.8 + lobe);
    rgb[3 * m + 1] = static_cast<float>(sky * 0.9 + 0.9 * lobe);
    rgb[3 * m + 2] = static_cast<float>(sky * 1.2 + 0.7 * lobe);
  }
  return rgb;
}

}  // namespace wavebake::testing
