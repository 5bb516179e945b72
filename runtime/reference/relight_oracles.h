#pragma once
// The slow, obviously right ways to compute B = T·L: the oracles of the
// relighting tests and the dense baseline of bench/relight.cc. They share no
// code with Relighter's Eq. 8 path (runtime/relight/relighter.h) beyond the column
// transform itself.
#include <span>
#include <vector>

#include "core/columns/compressed_columns.h"
#include "runtime/relight/lighting.h"

namespace wavebake {

// Eq. 3 of the 4D paper: every chosen column fully inverse-transformed on its
// own (Inverse2d to depth 0), weighted and summed in double, × albedo.
// cell_albedo: CellAlbedo(samples); rgb_out [W*H*3]. Lights whose column is out
// of range abort.
void NaiveRelight(const CompressedColumns& t, std::span<const float> cell_albedo,
                  std::span<const WaveletLight> lights, std::span<float> rgb_out);

// T decoded to the pixel domain of the sample grid (columns still in the row
// basis of the lights): column m is values[m*cells, (m+1)*cells).
struct DenseTransport {
  int width = 0, height = 0, columns = 0;
  std::vector<float> values;

  size_t cells() const { return static_cast<size_t>(width) * height; }
};

DenseTransport Densify(const CompressedColumns& t);

// Eq. 2, B[s] = Σ_m T[s,m] L[m] over every column (no approximation, zeros
// multiplied too: the dense matrix-vector product), × albedo.
// light_rgb: [3 * columns] (LightingCoefficients::rgb); rgb_out [W*H*3].
void DenseRelight(const DenseTransport& t, std::span<const float> light_rgb,
                  std::span<const float> cell_albedo, std::span<float> rgb_out);

}  // namespace wavebake
