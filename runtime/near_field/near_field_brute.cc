#include "runtime/near_field/near_field_brute.h"

#include <algorithm>
#include <cmath>

#include "core/util/parallel_for.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

struct Tap {
  int q;
  float w;
};

// The box weights of one axis: face texel i (of n) takes Σ w·source[q] over
// its taps, w = n/s · |footprint ∩ source texel q| (source texels 1/r wide).
void AxisTaps(int n, int r, double s, double o, std::vector<int>& first, std::vector<Tap>& taps) {
  first.assign(n + 1, 0);
  taps.clear();
  for (int i = 0; i < n; ++i) {
    const double q0 = s * i / n + o, q1 = s * (i + 1) / n + o;  // footprint in [0,1] units
    const int lo = std::max(0, static_cast<int>(std::floor(q0 * r)));
    const int hi = std::min(r - 1, static_cast<int>(std::ceil(q1 * r)) - 1);
    for (int q = lo; q <= hi; ++q) {
      const double len = std::min(q1, (q + 1.0) / r) - std::max(q0, double(q) / r);
      if (len > 0) taps.push_back({q, static_cast<float>(len * n / s)});
    }
    first[i + 1] = static_cast<int>(taps.size());
  }
}

struct Scratch {
  std::vector<int> first_x, first_y;
  std::vector<Tap> taps_x, taps_y;
  std::vector<float> rows;  // [r][n][3]: the canvas rows resampled along x
  std::vector<float> face;  // [n*n*3]
};

// The face image into s.face; false when the point does not see the light.
// kPerTexel: each texel its own footprint mean over the canvas texels it
// covers (Σ_qy Σ_qx w_y w_x F); kSeparable: the same weights applied along
// x to the canvas rows, then along y (the footprints of an axis-aligned face
// are a product, the structure the wavelet path's two steps use too).
bool Resample(const PlaneFace& face, const LightCanvas& c, Vec3 p, BruteResample mode, Scratch& s) {
  const FaceView v = ViewFrom(face, c, p);
  if (!v.lit) return false;
  const int n = face.n(), r = c.res;
  AxisTaps(n, r, v.map.s_x, v.map.o_x, s.first_x, s.taps_x);
  AxisTaps(n, r, v.map.s_y, v.map.o_y, s.first_y, s.taps_y);
  if (s.taps_y.empty()) return false;
  s.face.assign(size_t(n) * n * 3, 0.0f);
  if (mode == BruteResample::kPerTexel) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        float acc[3] = {0, 0, 0};
        for (int ty = s.first_y[y]; ty < s.first_y[y + 1]; ++ty) {
          const Tap& a = s.taps_y[ty];
          const float* row = &c.rgb[size_t(a.q) * r * 3];
          for (int tx = s.first_x[x]; tx < s.first_x[x + 1]; ++tx) {
            const Tap& b = s.taps_x[tx];
            const float w = a.w * b.w;
            for (int ch = 0; ch < 3; ++ch) acc[ch] += w * row[3 * b.q + ch];
          }
        }
        for (int ch = 0; ch < 3; ++ch) s.face[(size_t(y) * n + x) * 3 + ch] = acc[ch];
      }
    }
    return true;
  }
  // Only the canvas rows some face row takes.
  int q_lo = r, q_hi = -1;
  for (const Tap& t : s.taps_y) q_lo = std::min(q_lo, t.q), q_hi = std::max(q_hi, t.q);
  s.rows.resize(size_t(r) * n * 3);
  for (int q = q_lo; q <= q_hi; ++q) {
    const float* src = &c.rgb[size_t(q) * r * 3];
    float* dst = &s.rows[size_t(q) * n * 3];
    for (int x = 0; x < n; ++x) {
      float acc[3] = {0, 0, 0};
      for (int t = s.first_x[x]; t < s.first_x[x + 1]; ++t) {
        const Tap& tap = s.taps_x[t];
        for (int ch = 0; ch < 3; ++ch) acc[ch] += tap.w * src[3 * tap.q + ch];
      }
      for (int ch = 0; ch < 3; ++ch) dst[3 * x + ch] = acc[ch];
    }
  }
  for (int y = 0; y < n; ++y) {
    float* dst = &s.face[size_t(y) * n * 3];
    for (int t = s.first_y[y]; t < s.first_y[y + 1]; ++t) {
      const Tap& tap = s.taps_y[t];
      const float* src = &s.rows[size_t(tap.q) * n * 3];
      for (int i = 0; i < 3 * n; ++i) dst[i] += tap.w * src[i];
    }
  }
  return true;
}

}  // namespace

BruteForceNearField::BruteForceNearField(const NearFieldStore& store) : store_(store) {
  const int n = store.face.n(), m = n * n, cells = store.rows.cells();
  pixel_rows_.assign(size_t(cells) * m, 0.0f);
  for (int cell = 0; cell < cells; ++cell) {
    const float* row = store.rows.Row(cell);
    if (!row) continue;
    std::span<float> out(&pixel_rows_[size_t(cell) * m], m);
    std::copy(row, row + m, out.begin());
    Inverse2d(WaveletFilter::kHaar, out, n, n, MaxDepth(n, n));
  }
}

std::vector<float> BruteForceNearField::FaceImage(const LightCanvas& canvas, Vec3 p) const {
  Scratch s;
  if (!Resample(store_.face, canvas, p, BruteResample::kSeparable, s))
    s.face.assign(3 * store_.face.texels(), 0.0f);
  return s.face;
}

void BruteForceNearField::Relight(std::span<const LightCanvas> lights, int threads,
                                  std::span<float> rgb_out, BruteResample mode) const {
  const SampleSet& samples = store_.samples;
  const int m = store_.face.texels();
  ParallelChunks(
      samples.cells(), 512, threads, [] { return Scratch{}; },
      [&](Scratch& s, int begin, int end) {
        for (int cell = begin; cell < end; ++cell) {
          double sum[3] = {0, 0, 0};
          const int32_t id = samples.grid[cell];
          for (size_t li = 0; id >= 0 && li < lights.size(); ++li) {
            if (!Resample(store_.face, lights[li], samples.position[id], mode, s)) continue;
            const float* t = &pixel_rows_[size_t(cell) * m];
            float acc[3] = {0, 0, 0};
            for (int k = 0; k < m; ++k)
              for (int ch = 0; ch < 3; ++ch) acc[ch] += t[k] * s.face[3 * k + ch];
            for (int ch = 0; ch < 3; ++ch) sum[ch] += acc[ch];
          }
          for (int ch = 0; ch < 3; ++ch) rgb_out[3 * size_t(cell) + ch] = float(sum[ch]);
        }
      });
  MultiplyAlbedo(samples, rgb_out);
}

}  // namespace wavebake
