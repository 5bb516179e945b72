#pragma once
// Relighting from an adaptively compressed transport matrix: Eq. 8 of the 4D
// paper (§4.5, Fig. 6; DESIGN.md §1 "Relighting").
//
//   B = Σ_l S'_{l→l+1}( Σ_{i ∈ N(l)} w^i C^i )
//
// Column C^i is stored at its own transform depth d_i (CompressedColumns).
// The lights are grouped by that depth, deepest first; each group is added
// sparsely into one W×H×3 buffer, and one single-step inverse column
// transform (InverseStep of core/wavelets/wavelet2d.h) takes the buffer one level
// towards the pixel domain before the next, shallower group is added. So a
// frame costs one sparse add per kept coefficient of the chosen columns plus
// at most one full inverse transform, whatever n is. The result is the
// transport-weighted irradiance per grid cell; × the per-sample RGB albedo
// (factored out of T, DESIGN.md §1) it is the outgoing radiance.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "core/columns/compressed_columns.h"
#include "core/layouts/samples.h"
#include "runtime/relight/lighting.h"

namespace wavebake {

// The checks every reader of a decoded matrix makes: sizes, indptr monotone,
// positions inside the grid, depths ≤ MaxDepth(W, H); errors name the field.
absl::Status CheckColumns(const CompressedColumns& columns);

// Per-cell RGB albedo of a sample grid, [W*H*3] at 3*(y*W + x) + c; masked
// cells (grid −1) are NaN, so any radiance multiplied by them is NaN too.
std::vector<float> CellAlbedo(const SampleSet& samples);

// The checks of Relighter::Create (sizes, indptr monotone, positions inside
// the grid, depths ≤ MaxDepth(W, H), samples on the same grid), for other
// readers of the same matrix (runtime/relight/cell_rows.h).
absl::Status CheckRelightable(const CompressedColumns& columns, const SampleSet& samples);

class Relighter {
 public:
  // Checks the matrix (sizes, indptr monotone, positions inside the grid,
  // depths ≤ MaxDepth(W, H)) and that the samples lie on the same grid;
  // errors name the bad field.
  static absl::StatusOr<Relighter> Create(const CompressedColumns& columns,
                                          const SampleSet& samples);

  int width() const { return width_; }
  int height() const { return height_; }
  int cells() const { return width_ * height_; }
  int light_res() const { return light_res_; }
  int columns() const { return static_cast<int>(depth_.size()); }
  WaveletFilter row_filter() const { return row_filter_; }
  WaveletFilter column_filter() const { return column_filter_; }
  int64_t nonzeros() const { return static_cast<int64_t>(entries_.size()); }
  int depth(int column) const { return depth_[column]; }
  std::span<const float> cell_albedo() const { return albedo_; }

  // Eq. 8: rgb_out [W*H*3] = (Σ_i w^i S'(C^i)) × albedo, masked cells NaN.
  // The lights may come in any order and repeat columns; their columns must
  // be < columns() and lights.light_res == light_res() (checked: a violation
  // is a programming error and aborts). Allocates nothing once the scratch
  // has grown to the largest light count seen. Not thread-safe: the scratch
  // is per Relighter; use one Relighter per thread.
  void Relight(const WaveletLights& lights, std::span<float> rgb_out);
  // The same before the albedo: Σ_i w^i S'(C^i) at every cell, masked ones
  // included (they hold whatever the columns hold there, usually 0).
  void RelightTransport(std::span<const WaveletLight> lights, std::span<float> rgb_out);
  // rgb_out = transport_rgb × cell albedo (NaN in masked cells); may alias.
  void ApplyAlbedo(std::span<const float> transport_rgb, std::span<float> rgb_out) const;

 private:
  // Position and value of one kept coefficient, side by side so a column is
  // one contiguous stream.
  struct Entry {
    uint32_t position;
    float value;
  };

  // Enough for MaxDepth of a 4096² grid (12), the largest layout.
  static constexpr int kDepthSlots = 16;

  Relighter() = default;
  // Counting sort of the lights by their column's depth into order_ (deepest
  // first); group d is order_[group_start_[d], group_start_[d] +
  // group_count_[d]). Returns the deepest depth present (−1: no lights).
  int SortByDepth(std::span<const WaveletLight> lights);
  // Eq. 8 into planes_: sparse adds per depth group, one InverseStep between.
  void Accumulate(std::span<const WaveletLight> lights);
  void AddColumn(const WaveletLight& light);

  int width_ = 0, height_ = 0, light_res_ = 0;
  WaveletFilter row_filter_ = WaveletFilter::kHaar;
  WaveletFilter column_filter_ = WaveletFilter::kHaar;
  std::vector<int64_t> first_;  // [M+1] CSC column pointers into entries_
  std::vector<Entry> entries_;
  std::vector<uint8_t> depth_;  // [M]
  std::vector<float> albedo_;   // [cells*3], NaN where masked

  // Per-frame scratch: the three channel planes and the depth-sorted lights.
  std::vector<float> planes_;  // [3 * cells], channel-major (InverseStep wants planes)
  std::vector<const WaveletLight*> order_;
  std::array<uint32_t, kDepthSlots> group_start_{}, group_count_{};
};

}  // namespace wavebake
