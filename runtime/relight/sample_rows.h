#pragma once
// Per-sample lighting (DESIGN.md §1 "Per-sample lighting"): when the lighting
// factor differs per sample — a sample's glossy BRDF slice times the
// environment (the triple product, runtime/glossy/glossy_relighter.h), a near-field
// light's image on the cubemap — relighting is, per grid cell x,
//
//   B(x) = Σ_j R_j(x) · W_j(x)
//
// with R the store's matrix in the row basis and W(x) the cell's weights in
// the same basis. Eq. 8's grouping by shared lights no longer applies, so the
// 4D-compressed columns are decoded once, at load: every column image
// through the inverse column transform at its own depth, its nonzero cells
// kept as per-cell sparse rows. The matrix is static, so no frame decodes
// anything again; a frame is one sparse dot product per cell against
// whatever RgbCube (core/directions/rgb_cube.h) the caller filled, restricted to the
// faces it touched.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/columns/compressed_columns.h"
#include "core/directions/rgb_cube.h"

namespace wavebake {

// Column m's image over the grid (width·height floats, overwritten): its
// kept coefficients through the inverse column transform at its own depth
// (4D paper §4.2). The one column decoder of both per-sample row forms,
// SampleRows (sparse, cube stores) and CellRows (dense, runtime/relight/cell_rows.h).
void DecodeColumnImage(const CompressedColumns& t, int m, std::span<float> image);

class SampleRows {
 public:
  SampleRows() = default;  // no cells
  struct Stats {
    int64_t nonzeros = 0;  // kept row entries, all cells
    size_t bytes = 0;      // memory of the rows
    double seconds = 0;    // decode and transpose
  };

  // Decodes every column (Relighter::Create's checks apply: sizes, depths,
  // positions; errors name the field). Entries with |value| ≤ drop_below are
  // dropped (0: only exact zeros, which is every cell no kept basis function
  // of the column reaches). Uses all cores; the result does not depend on
  // their number.
  static absl::StatusOr<SampleRows> Decode(const CompressedColumns& columns, float drop_below = 0);

  int width() const { return width_; }
  int height() const { return height_; }
  int cells() const { return width_ * height_; }
  int light_res() const { return light_res_; }
  const Stats& stats() const { return stats_; }

  // The index among all entries of the first entry of (cell, face); the
  // entries of a row face are consecutive. entries() in all.
  int64_t EntryOf(int cell, int face) const { return first_[cell * 6 + face]; }
  int64_t entries() const { return first_.empty() ? 0 : first_.back(); }

  // Row of `cell` restricted to `face`: row-basis indices (increasing) and values.
  std::span<const uint32_t> terms(int cell, int face) const;
  std::span<const float> values(int cell, int face) const;

  // Σ_j R_j(cell) · w_j over the faces w touched, per channel: weights
  // given densely.
  std::array<float, 3> Dot(int cell, const RgbCube& w) const;

  // The same with the weights asked for where the row has entries only:
  // for every face in `faces` holding some, weights(face, terms, entry, rgb)
  // must fill rgb[3k + c] with W_{terms[k]}(cell) (a weight that is cheap per
  // term — the triple product's, a near-field light's — need not be formed
  // on the whole cube). `entry` numbers terms[0] among all rows' entries
  // (EntryOf), so a caller can keep static data per entry. scratch: reused
  // between calls.
  template <typename Weights>
  std::array<float, 3> Apply(int cell, const std::array<bool, 6>& faces, Weights&& weights,
                             std::vector<float>& scratch) const {
    float b[3] = {0, 0, 0};
    for (int face = 0; face < 6; ++face) {
      if (!faces[face]) continue;
      const int64_t begin = first_[cell * 6 + face], end = first_[cell * 6 + face + 1];
      if (begin == end) continue;
      scratch.resize(3 * static_cast<size_t>(end - begin));
      weights(face, std::span<const uint32_t>(terms_.data() + begin, end - begin), begin,
              std::span<float>(scratch));
      for (int64_t k = begin; k < end; ++k) {
        const float v = values_[k];
        const float* w = scratch.data() + 3 * (k - begin);
        b[0] += v * w[0];
        b[1] += v * w[1];
        b[2] += v * w[2];
      }
    }
    return {b[0], b[1], b[2]};
  }

 private:
  int width_ = 0, height_ = 0, light_res_ = 0;
  std::vector<int64_t>
      first_;  // [cells·6 + 1]: segment (cell, face) is [first_[6c+f], first_[6c+f+1])
  std::vector<uint32_t> terms_;
  std::vector<float> values_;
  Stats stats_;
};

}  // namespace wavebake
