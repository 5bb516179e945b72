// Where the compression fails (issue 7, docs/RESULTS.md "Where methods
// fail"), through the real pipeline on a real scene: one trace, then the
// column stage and FINALIZE rerun per setting on the same staging.
//   * Full 4D inflation: the full-depth column transform keeps MORE
//     coefficients than the 2D (pixel-domain) columns for the finest row
//     levels, whose columns are a few isolated shadow-edge cells that a deep
//     transform smears over every scale (4D paper §4.4, Fig. 8); the adaptive
//     mode, trying every depth, never keeps more than either.
//   * Too few bits: the quantization error follows the subtractive-dither law
//     Σ n_c (scale_c/Q_b)²/12 (core/quantizer.h) and so grows ~2× per bit
//     dropped, past the target well before 4 bits; --bits auto stays within
//     the half target it promises (DESIGN.md §1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "core/bake_params.h"
#include "core/subband.h"
#include "storage/store_reader.h"
#include "tests/worker/column_test_support.h"
#include "worker/bake_context.h"
#include "worker/bake_tile.h"
#include "worker/finalize.h"
#include "worker/staging.h"
#include "worker/transform_columns.h"

namespace wavebake {
namespace {

using column_testing::ScratchDir;

// cubes-wall through a 32×32 camera, N = 8 (384 columns): sharp cube and wall
// shadows on flat receivers.
BakeParams SmallJob() {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 1;
  p.layout = "camera:32x32";
  p.tile_size = 16;
  p.column_group = 128;
  return p;
}
constexpr char kScene[] = "builtin:cubes-wall";

// A traced job whose staging is kept, so each setting reruns only the
// column stage and FINALIZE.
class StagedJob {
 public:
  StagedJob() {
    auto ctx = MakeBakeContext(kScene, SmallJob());
    EXPECT_TRUE(ctx.ok()) << ctx.status();
    if (!ctx.ok()) return;
    store_ = dir_.path() / "job.wbk";
    EXPECT_TRUE(CreateStaging((*ctx)->plan, store_).ok());
    for (int t = 0; t < (*ctx)->plan.tiles(); ++t)
      EXPECT_TRUE(BakeTile(**ctx, store_, t, nullptr).ok());
  }

  // The dequantized matrix of the store made with `p` (same plan as SmallJob).
  CompressedColumns Compress(const BakeParams& p, int* bits_used = nullptr) const {
    auto ctx = MakeBakeContext(kScene, p);
    EXPECT_TRUE(ctx.ok()) << ctx.status();
    for (int g = 0; g < (*ctx)->plan.groups; ++g)
      EXPECT_TRUE(TransformColumns(**ctx, store_, g, nullptr).ok());
    EXPECT_TRUE(Finalize(**ctx, store_, {.keep_staging = true}).ok());
    if (bits_used != nullptr) {
      absl::StatusOr<StoreInfo> info = ReadStoreInfo(store_);
      EXPECT_TRUE(info.ok()) << info.status();
      *bits_used = info.ok() ? info->bits : 0;
    }
    absl::StatusOr<CompressedColumns> columns = ReadTransport(store_);
    EXPECT_TRUE(columns.ok()) << columns.status();
    return *std::move(columns);
  }

 private:
  ScratchDir dir_;
  std::filesystem::path store_;
};

const StagedJob& Job() {
  static const StagedJob job;  // traced once for the whole file
  return job;
}

int64_t Kept(const CompressedColumns& c, int m) { return c.indptr[m + 1] - c.indptr[m]; }

// Row-transform level (core/subband.h RowLevel) of light column m.
int RowLevelOf(int m, int n) {
  const int texel = m % (n * n);
  return RowLevel(texel % n, texel / n);
}

TEST(FailureCompressionTest, FullDepthInflatesFineRowLevelsAndAdaptiveDoesNot) {
  std::map<ColumnMode, CompressedColumns> by_mode;
  for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kFull, ColumnMode::kAdaptive}) {
    BakeParams p = SmallJob();
    p.column_mode = mode;
    p.target_error = 0.01;
    by_mode[mode] = Job().Compress(p);
  }
  const CompressedColumns& flat = by_mode[ColumnMode::k2d];
  const CompressedColumns& full = by_mode[ColumnMode::kFull];
  const CompressedColumns& adaptive = by_mode[ColumnMode::kAdaptive];
  const int n = flat.light_res;
  const int finest = RowLevelOf(n - 1, n);  // texel (N−1, 0): finest detail level
  int64_t kept_2d = 0, kept_full = 0, kept_adaptive = 0;
  for (int m = 0; m < flat.columns; ++m) {
    // Per column: adaptive tries depth 0 (= 2d) and max (= full) among others.
    ASSERT_LE(Kept(adaptive, m), Kept(flat, m)) << "column " << m;
    ASSERT_LE(Kept(adaptive, m), Kept(full, m)) << "column " << m;
    if (RowLevelOf(m, n) != finest) continue;
    kept_2d += Kept(flat, m);
    kept_full += Kept(full, m);
    kept_adaptive += Kept(adaptive, m);
  }
  ASSERT_GT(kept_2d, 0);
  EXPECT_GT(kept_full, kept_2d) << "full 4D should inflate the finest row level";
  EXPECT_LE(kept_adaptive, kept_2d);
}

// Σ over kept coefficients of (a − b)², with both stores' positions equal.
double DifferenceEnergy(const CompressedColumns& a, const CompressedColumns& b) {
  double e = 0;
  for (size_t i = 0; i < a.values.size(); ++i) e += std::pow(double(a.values[i]) - b.values[i], 2);
  return e;
}

// The subtractive-dither law for a 2d store (every coefficient at level 0):
// each column's error is uniform over one step scale_c/Q, variance step²/12.
double ExpectedDitherEnergy(const CompressedColumns& reference, int bits) {
  const double q = std::ldexp(1.0, bits - 1) - 1;
  double e = 0;
  for (int m = 0; m < reference.columns; ++m) {
    double scale = 0;
    for (int64_t i = reference.indptr[m]; i < reference.indptr[m + 1]; ++i)
      scale = std::max(scale, std::abs(double(reference.values[i])));
    e += Kept(reference, m) * std::pow(scale / q, 2) / 12;
  }
  return e;
}

TEST(FailureCompressionTest, TooFewBitsFollowsTheDitherLawAndPassesTheTarget) {
  constexpr double kTarget = 0.01;
  BakeParams p = SmallJob();
  p.column_mode = ColumnMode::k2d;
  p.target_error = kTarget;
  p.bits = 16;  // the reference: steps 2^-15 of each column's scale
  const CompressedColumns fine = Job().Compress(p);
  double energy = 0;
  for (float v : fine.values) energy += double(v) * v;
  ASSERT_GT(fine.values.size(), 1000u);

  double previous = 0;
  for (int bits : {12, 10, 8, 6, 5, 4, 3}) {
    p.bits = bits;
    const CompressedColumns coarse = Job().Compress(p);
    ASSERT_EQ(coarse.indices, fine.indices) << "selection must not depend on bits";
    const double measured = DifferenceEnergy(coarse, fine);
    const double expected = ExpectedDitherEnergy(fine, bits);
    EXPECT_NEAR(measured / expected, 1.0, 0.15) << bits << " bits";
    const double rel = std::sqrt(measured / energy);
    EXPECT_GT(rel, 1.5 * previous) << bits << " bits: error must grow as bits drop";
    previous = rel;
    if (bits >= 12) EXPECT_LT(rel, kTarget / 2) << bits << " bits";
    if (bits <= 4) EXPECT_GT(rel, kTarget) << bits << " bits: past the target";
  }

  // --bits auto promises quantization error ≤ target/2 of the matrix energy.
  p.bits = 0;
  int chosen = 0;
  const CompressedColumns automatic = Job().Compress(p, &chosen);
  EXPECT_GE(chosen, 5);
  EXPECT_LE(std::sqrt(DifferenceEnergy(automatic, fine) / energy), 1.1 * kTarget / 2)
      << "bits auto chose " << chosen;
}

}  // namespace
}  // namespace wavebake
