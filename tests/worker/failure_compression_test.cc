// Where the compression fails (docs/RESULTS.md "Where methods
// fail"), through the real pipeline on a real scene: one trace, then the
// column stage and FINALIZE rerun per setting on the same staging.
//   * Full 4D inflation: where column images are rough at every scale — the
//     bunny's vertices on a Hilbert layout, neighbours on the grid only
//     roughly neighbours on the surface — the full-depth column transform
//     keeps MORE coefficients than the 2D (pixel-domain) columns: a deep
//     transform smears isolated values over every scale (4D paper §4.4). The
//     adaptive mode, trying every depth, keeps no more than either per column
//     (or exactly 2d's coding, when that codes smaller), and its store is
//     never larger than either in bytes.
//   * Too few bits: the quantization error follows the subtractive-dither law
//     Σ n_c (scale_c/Q_b)²/12 (core/columns/quantizer.h) and so grows ~2× per bit
//     dropped, past the target well before 4 bits; --bits auto stays within
//     the half target it promises (DESIGN.md §1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/bake/bake_params.h"
#include "core/wavelets/subband.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "tests/worker/column_test_support.h"
#include "worker/columns/finalize.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using column_testing::ScratchDir;

// N = 8 (384 columns), one direction per texel: small and deterministic.
BakeParams SmallJob(const std::string& layout, int light_res = 8) {
  BakeParams p;
  p.light_res = light_res;
  p.supersample = 1;
  p.layout = layout;
  p.tile_size = 32;
  p.column_group = 128;
  return p;
}

// A traced job whose staging is kept, so each setting reruns only the
// column stage and FINALIZE.
class StagedJob {
 public:
  StagedJob(std::string scene, std::string layout, int light_res = 8)
      : scene_(scene), layout_(layout), light_res_(light_res) {
    auto ctx = MakeBakeContext(scene_, SmallJob(layout_, light_res_));
    EXPECT_TRUE(ctx.ok()) << ctx.status();
    if (!ctx.ok()) return;
    store_ = dir_.path() / "job.wbk";
    EXPECT_TRUE(CreateStaging((*ctx)->plan, store_).ok());
    for (int t = 0; t < (*ctx)->plan.tiles(); ++t)
      EXPECT_TRUE(BakeTile(**ctx, store_, t, nullptr).ok());
  }

  BakeParams Params() const { return SmallJob(layout_, light_res_); }

  // The dequantized matrix of the store made with `p` (Params() changed only
  // in column-stage fields: same plan).
  CompressedColumns Compress(const BakeParams& p, int* bits_used = nullptr,
                             int64_t* transport_bytes = nullptr) const {
    // FINALIZE refuses to overwrite an array of another shape: the previous
    // setting's output goes first, staging stays.
    for (const char* name : {store::kTransport, store::kSamples, ".zattrs"})
      std::filesystem::remove_all(store_ / name);
    auto ctx = MakeBakeContext(scene_, p);
    EXPECT_TRUE(ctx.ok()) << ctx.status();
    for (int g = 0; g < (*ctx)->plan.groups; ++g)
      EXPECT_TRUE(TransformColumns(**ctx, store_, g, nullptr).ok());
    EXPECT_TRUE(Finalize(**ctx, store_, {.keep_staging = true}).ok());
    if (bits_used != nullptr) {
      absl::StatusOr<StoreInfo> info = ReadStoreInfo(store_);
      EXPECT_TRUE(info.ok()) << info.status();
      *bits_used = info.ok() ? info->bits : 0;
    }
    if (transport_bytes != nullptr) {
      absl::StatusOr<StoreInfo> info = ReadStoreInfo(store_);
      EXPECT_TRUE(info.ok()) << info.status();
      *transport_bytes = info.ok() ? info->attrs["stats"]["bytes"]["transport"].get<int64_t>() : 0;
    }
    absl::StatusOr<CompressedColumns> columns = ReadTransport(store_);
    EXPECT_TRUE(columns.ok()) << columns.status();
    return *std::move(columns);
  }

 private:
  std::string scene_, layout_;
  int light_res_;
  ScratchDir dir_;
  std::filesystem::path store_;
};

// cubes-wall through a 32×32 camera: sharp cube and wall shadows on flat
// receivers, smooth column images.
const StagedJob& CubesWall() {
  static const StagedJob job("builtin:cubes-wall", "camera:32x32");  // traced once
  return job;
}

// cubes-wall at 64×64 samples and N = 16: big enough that the store is not
// dominated by its smallest columns (at 32×32, N = 8 the adaptive store keeps
// only 1.9× fewer coefficients than 2d and is larger in bytes either way).
const StagedJob& CubesWall64() {
  static const StagedJob job("builtin:cubes-wall", "camera:64x64", 16);
  return job;
}

// The bunny on a Hilbert layout: 2503 vertices along a 2D Hilbert curve, so
// grid neighbours are only roughly surface neighbours and the column images
// are rough at every scale.
const StagedJob& HilbertBunny() {
  static const StagedJob job(std::string(WB_SHARED_DATA) + "/models/bunny.obj", "hilbert:64x64");
  return job;
}

int64_t Kept(const CompressedColumns& c, int m) { return c.indptr[m + 1] - c.indptr[m]; }

// Row-transform level (core/wavelets/subband.h RowLevel) of light column m.
int RowLevelOf(int m, int n) {
  const int texel = m % (n * n);
  return RowLevel(texel % n, texel / n);
}

// Adaptive is never larger in bytes than either fixed depth on a Hilbert
// mesh, at any target (DESIGN.md §1). Chosen by coefficient count alone it
// was larger than 2d at the low targets, where the counts of all depths come
// close and a deep coefficient costs more bits than a depth-0 one.
TEST(FailureCompressionTest, AdaptiveIsNoLargerThanTwoDOrFullInBytesOnAHilbertMesh) {
  for (double target : {0.003, 0.01, 0.03}) {
    std::map<ColumnMode, int64_t> bytes;
    for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kFull, ColumnMode::kAdaptive}) {
      BakeParams p = HilbertBunny().Params();
      p.column_mode = mode;
      p.target_error = target;
      HilbertBunny().Compress(p, nullptr, &bytes[mode]);
    }
    std::cout << "target " << target << ": bytes 2d " << bytes[ColumnMode::k2d] << ", full "
              << bytes[ColumnMode::kFull] << ", adaptive " << bytes[ColumnMode::kAdaptive] << "\n";
    EXPECT_LE(bytes[ColumnMode::kAdaptive], bytes[ColumnMode::k2d]) << "target " << target;
    EXPECT_LE(bytes[ColumnMode::kAdaptive], bytes[ColumnMode::kFull]) << "target " << target;
  }
}

// Measured (seed 1): 2d keeps 436 501 coefficients, full 466 588 (+7 %, and
// more at every row level), adaptive 420 277. On the camera and grid scenes
// full keeps 2–10× fewer than 2d instead (docs/RESULTS.md chart 1).
TEST(FailureCompressionTest, FullDepthInflatesARoughLayoutAndAdaptiveDoesNot) {
  std::map<ColumnMode, CompressedColumns> by_mode;
  for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kFull, ColumnMode::kAdaptive}) {
    BakeParams p = HilbertBunny().Params();
    p.column_mode = mode;
    p.target_error = 0.01;
    by_mode[mode] = HilbertBunny().Compress(p);
  }
  const CompressedColumns& flat = by_mode[ColumnMode::k2d];
  const CompressedColumns& full = by_mode[ColumnMode::kFull];
  const CompressedColumns& adaptive = by_mode[ColumnMode::kAdaptive];
  const int n = flat.light_res;
  std::map<int, int64_t> kept_2d, kept_full, kept_adaptive;  // by row level
  for (int m = 0; m < flat.columns; ++m) {
    // Per column: adaptive tries depth 0 (= 2d) and the maximum (= full),
    // keeping the fewest coefficients or depth 0's coding when its bits are
    // fewer (core/columns/group_codings.h).
    if (adaptive.depth[m] == 0) {
      ASSERT_EQ(Kept(adaptive, m), Kept(flat, m)) << "column " << m;
    } else {
      ASSERT_LE(Kept(adaptive, m), Kept(flat, m)) << "column " << m;
      ASSERT_LE(Kept(adaptive, m), Kept(full, m)) << "column " << m;
    }
    kept_2d[RowLevelOf(m, n)] += Kept(flat, m);
    kept_full[RowLevelOf(m, n)] += Kept(full, m);
    kept_adaptive[RowLevelOf(m, n)] += Kept(adaptive, m);
  }
  int64_t total_2d = 0, total_full = 0, total_adaptive = 0;
  for (const auto& [level, kept] : kept_2d) {
    EXPECT_GT(kept_full[level], kept) << "full 4D should inflate row level " << level;
    EXPECT_LE(kept_adaptive[level], kept) << "row level " << level;
    total_2d += kept;
    total_full += kept_full[level];
    total_adaptive += kept_adaptive[level];
  }
  EXPECT_GT(total_full, total_2d * 1.03);
  EXPECT_LT(total_adaptive, total_2d);
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
  BakeParams p = CubesWall().Params();
  p.column_mode = ColumnMode::k2d;
  p.target_error = kTarget;
  p.bits = 16;  // the reference: steps 2^-15 of each column's scale
  const CompressedColumns fine = CubesWall().Compress(p);
  double energy = 0;
  for (float v : fine.values) energy += double(v) * v;
  ASSERT_GT(fine.values.size(), 1000u);

  double previous = 0;
  for (int bits : {12, 10, 8, 6, 5, 4, 3}) {
    p.bits = bits;
    const CompressedColumns coarse = CubesWall().Compress(p);
    ASSERT_EQ(coarse.indices, fine.indices) << "selection must not depend on bits";
    const double measured = DifferenceEnergy(coarse, fine);
    const double expected = ExpectedDitherEnergy(fine, bits);
    EXPECT_NEAR(measured / expected, 1.0, 0.15) << bits << " bits";
    const double rel = std::sqrt(measured / energy);
    EXPECT_GT(rel, 1.5 * previous) << bits << " bits: error must grow as bits drop";
    previous = rel;
    if (bits >= 12) {
      EXPECT_LT(rel, kTarget / 2) << bits << " bits";
    }
    if (bits <= 4) {
      EXPECT_GT(rel, kTarget) << bits << " bits: past the target";
    }
  }

  // --bits auto promises quantization error ≤ target/2 of the matrix energy.
  p.bits = 0;
  int chosen = 0;
  const CompressedColumns automatic = CubesWall().Compress(p, &chosen);
  EXPECT_GE(chosen, 5);
  EXPECT_LE(std::sqrt(DifferenceEnergy(automatic, fine) / energy), 1.1 * kTarget / 2)
      << "bits auto chose " << chosen;
}

// Bytes, not coefficients, are what users pay for. On cubes-wall
// (64×64 samples, N = 16) the adaptive store keeps 3.6× fewer coefficients
// than 2d, yet with the paper's 2^l level scaling (its values cost ~l more
// bits each) it is no smaller in bytes: 1.00× here, and 0.99× with the
// per-column max coding before the uniform step (2d 830 KB, adaptive 834 KB;
// 1.13× at N = 32). The
// uniform, error-budgeted step turns the coefficient win into a byte win at
// the same target and error budget.
TEST(FailureCompressionTest, AdaptiveWinsInBytesWithTheUniformStep) {
  std::map<std::pair<LevelScaling, ColumnMode>, int64_t> bytes;
  std::map<ColumnMode, size_t> nnz;
  for (LevelScaling s : {LevelScaling::kUniform, LevelScaling::kPaper}) {
    for (ColumnMode mode : {ColumnMode::k2d, ColumnMode::kAdaptive}) {
      BakeParams p = CubesWall64().Params();
      p.column_mode = mode;
      p.target_error = 0.01;
      p.level_scaling = s;
      nnz[mode] = CubesWall64().Compress(p, nullptr, &bytes[{s, mode}]).values.size();
    }
  }
  const auto ratio = [&](LevelScaling s) {
    return double(bytes[{s, ColumnMode::k2d}]) / double(bytes[{s, ColumnMode::kAdaptive}]);
  };
  const int64_t uniform = bytes[{LevelScaling::kUniform, ColumnMode::kAdaptive}];
  const int64_t paper = bytes[{LevelScaling::kPaper, ColumnMode::kAdaptive}];
  std::cout << "2d/adaptive: coefficients "
            << double(nnz[ColumnMode::k2d]) / nnz[ColumnMode::kAdaptive] << ", bytes uniform "
            << ratio(LevelScaling::kUniform) << ", paper " << ratio(LevelScaling::kPaper)
            << "; adaptive bytes uniform " << uniform << ", paper " << paper << "\n";
  EXPECT_GT(double(nnz[ColumnMode::k2d]) / nnz[ColumnMode::kAdaptive], 3);
  EXPECT_GT(ratio(LevelScaling::kUniform), 1.15);
  EXPECT_LT(ratio(LevelScaling::kPaper), 1.1);  // the old value coding does not win
  EXPECT_LT(uniform, 0.9 * paper);
}

}  // namespace
}  // namespace wavebake
