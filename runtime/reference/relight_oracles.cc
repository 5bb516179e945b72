#include "runtime/reference/relight_oracles.h"

#include <algorithm>
#include <cstdlib>

#include "core/util/check_or_die.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

// Column m as a W×H image at depth 0 (pixel domain).
void DecodeColumn(const CompressedColumns& t, int m, std::span<float> img) {
  std::fill(img.begin(), img.end(), 0.0f);
  for (int64_t k = t.indptr[m]; k < t.indptr[m + 1]; ++k) img[t.indices[k]] = t.values[k];
  Inverse2d(t.column_filter, img, t.width, t.height, t.depth[m]);
}

}  // namespace

void NaiveRelight(const CompressedColumns& t, std::span<const float> cell_albedo,
                  std::span<const WaveletLight> lights, std::span<float> rgb_out) {
  const size_t cells = static_cast<size_t>(t.width) * t.height;
  CheckOrDie("relight oracle", rgb_out.size() == 3 * cells && cell_albedo.size() == 3 * cells,
             "buffers are not W*H*3 floats");
  std::vector<double> sum(3 * cells, 0.0);
  std::vector<float> img(cells);
  for (const WaveletLight& l : lights) {
    CheckOrDie("relight oracle", l.column < static_cast<uint32_t>(t.columns),
               "light column out of range");
    DecodeColumn(t, static_cast<int>(l.column), img);
    for (size_t i = 0; i < cells; ++i) {
      for (int c = 0; c < 3; ++c) sum[3 * i + c] += double{l.weight[c]} * img[i];
    }
  }
  for (size_t i = 0; i < 3 * cells; ++i) {
    rgb_out[i] = static_cast<float>(sum[i] * cell_albedo[i]);
  }
}

DenseTransport Densify(const CompressedColumns& t) {
  DenseTransport d;
  d.width = t.width;
  d.height = t.height;
  d.columns = t.columns;
  d.values.resize(d.cells() * t.columns);
  for (int m = 0; m < t.columns; ++m) {
    DecodeColumn(t, m, std::span<float>(d.values.data() + m * d.cells(), d.cells()));
  }
  return d;
}

void DenseRelight(const DenseTransport& t, std::span<const float> light_rgb,
                  std::span<const float> cell_albedo, std::span<float> rgb_out) {
  const size_t cells = t.cells();
  CheckOrDie("relight oracle", rgb_out.size() == 3 * cells && cell_albedo.size() == 3 * cells,
             "buffers are not W*H*3 floats");
  CheckOrDie("relight oracle", light_rgb.size() == 3 * static_cast<size_t>(t.columns),
             "lighting is not 3*M floats");
  // Channel planes so each column is three contiguous axpys (vectorized).
  std::vector<float> planes(3 * cells, 0.0f);
  float* r = planes.data();
  float* g = r + cells;
  float* b = g + cells;
  for (int m = 0; m < t.columns; ++m) {
    const float* col = t.values.data() + m * cells;
    const float wr = light_rgb[3 * m], wg = light_rgb[3 * m + 1], wb = light_rgb[3 * m + 2];
    for (size_t i = 0; i < cells; ++i) {
      r[i] += wr * col[i];
      g[i] += wg * col[i];
      b[i] += wb * col[i];
    }
  }
  for (size_t i = 0; i < cells; ++i) {
    rgb_out[3 * i] = r[i] * cell_albedo[3 * i];
    rgb_out[3 * i + 1] = g[i] * cell_albedo[3 * i + 1];
    rgb_out[3 * i + 2] = b[i] * cell_albedo[3 * i + 2];
  }
}

}  // namespace wavebake
