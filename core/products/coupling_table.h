#pragma once
// The memory-based approach of Sun & Ramamoorthi §5.3.2: every nonzero 1D
// affine coupling coefficient D_ik(s, o) of an R-texel source axis against an
// N-texel target axis, precomputed on a grid of scales and offsets and looked
// up at the nearest grid point instead of being computed (core/products/haar_affine.h
// SourceCouplings, the "computed from canonical coefficients" approach).
//
// Grid: `scales` values of s, log-spaced over [s_min, s_max]; for each, `offsets`
// values of o spaced evenly over (−s, 1), the offsets at which the image of
// the source axis overlaps the target axis at all. Lookup snaps s and o to
// the nearest grid point, so the coefficients are those of a slightly moved
// and resized light: the table trades that error (and memory) for the
// arithmetic of Eq. 16–18.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/products/haar_affine.h"

namespace wavebake {

struct CouplingTableOptions {
  int source_res = 32;  // R: source axis texels (power of two)
  int target_res = 32;  // N: target axis texels (power of two)
  double s_min = 0.05, s_max = 20;
  int scales = 64, offsets = 256;
};

class CouplingTable {
 public:
  // Errors name the bad option (resolutions, range, counts).
  static absl::StatusOr<CouplingTable> Build(const CouplingTableOptions& options);

  const CouplingTableOptions& options() const { return options_; }
  size_t bytes() const;
  size_t entries() const { return entries_.size(); }
  double build_seconds() const { return build_seconds_; }

  // The couplings of source factor `source` (Haar1dId on the R axis) at the
  // grid point nearest (s, o); empty outside the grid's s range or o range.
  std::span<const Coupling1d> Lookup(int source, double s, double o) const;

 private:
  CouplingTable() = default;
  CouplingTableOptions options_;
  int factors_ = 0;
  double log_s_min_ = 0, log_s_step_ = 0;
  std::vector<uint32_t> first_;  // [(scale · offsets + offset) · factors + source + 1]
  std::vector<Coupling1d> entries_;
  double build_seconds_ = 0;
};

}  // namespace wavebake
