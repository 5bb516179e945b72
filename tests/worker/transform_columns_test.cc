// TRANSFORM_COLUMNS on synthetic matrices with known structure (DESIGN.md §1
// "Column transform", 4D paper §4.2): smooth columns compress with depth,
// isolated spikes inflate under a full transform, and the adaptive search
// never keeps more than either fixed choice.
#include "worker/columns/transform_columns.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "storage/store/store_layout.h"
#include "tests/worker/column_test_support.h"
#include "worker/columns/group_result.h"

namespace wavebake {
namespace {

using column_testing::KindOf;
using column_testing::MakeContext;
using column_testing::ScratchDir;
using column_testing::SyntheticKind;
using column_testing::SyntheticMatrix;
using column_testing::TransformAll;
using column_testing::WriteSyntheticStaging;

// N = 8 (M = 384 columns) over a 32×32 grid in 16×16 tiles; groups of 100
// leave a partial last group of 84 (padding rows in its staging chunks).
BakeParams SmallJob() {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 1;
  p.tile_size = 16;
  p.column_group = 100;
  return p;
}

// One synthetic staging shared by the tests of this file (writing it costs
// fsyncs, not arithmetic); only the column parameters vary between runs.
class SharedStaging {
 public:
  static SharedStaging& Get() {
    static SharedStaging shared;  // removed at exit
    return shared;
  }
  const std::filesystem::path& store() const { return store_; }

 private:
  SharedStaging() : store_(dir_.path() / "out.wbk") {
    auto ctx = MakeContext(SmallJob());
    WriteSyntheticStaging(ctx->plan, store_, SyntheticMatrix(ctx->plan.width, ctx->plan.height));
  }
  ScratchDir dir_;
  std::filesystem::path store_;
};

// Every column's GroupColumn after TRANSFORM_COLUMNS of the synthetic matrix.
std::vector<GroupColumn> CodeMatrix(const BakeParams& params) {
  const auto& store = SharedStaging::Get().store();
  auto ctx = MakeContext(params);
  TransformAll(*ctx, store);
  std::vector<GroupColumn> columns;
  for (int g = 0; g < ctx->plan.groups; ++g) {
    absl::StatusOr<GroupResult> r = ReadGroupResult(store, g);
    EXPECT_TRUE(r.ok()) << r.status();
    if (!r.ok()) return {};
    columns.insert(columns.end(), r->columns.begin(), r->columns.end());
  }
  return columns;
}

BakeParams WithMode(BakeParams p, ColumnMode mode) {
  p.column_mode = mode;
  return p;
}

// Adaptive keeps the coding with the fewest coefficients over every depth,
// unless depth 0's codes in fewer bits (core/columns/group_codings.h): a
// column is then coded exactly as 2d codes it.
TEST(TransformColumnsTest, AdaptiveKeepsNoMoreThanTwoDOrFullOrCodesAsTwoD) {
  for (ErrorScope scope : {ErrorScope::kMatrix, ErrorScope::kColumn}) {
    for (double target : {0.003, 0.01, 0.03}) {
      BakeParams p = SmallJob();
      p.target_error = target;
      p.error_scope = scope;
      const auto two_d = CodeMatrix(WithMode(p, ColumnMode::k2d));
      const auto full = CodeMatrix(WithMode(p, ColumnMode::kFull));
      const auto adaptive = CodeMatrix(WithMode(p, ColumnMode::kAdaptive));
      ASSERT_EQ(two_d.size(), 384u);
      ASSERT_EQ(full.size(), 384u);
      ASSERT_EQ(adaptive.size(), 384u);
      uint64_t kept_2d = 0, kept_full = 0, kept_adaptive = 0;
      for (size_t m = 0; m < adaptive.size(); ++m) {
        if (adaptive[m].depth == 0)
          EXPECT_EQ(adaptive[m].kept, two_d[m].kept) << "column " << m << " target " << target;
        else
          EXPECT_LE(adaptive[m].kept, std::min(two_d[m].kept, full[m].kept))
              << "column " << m << " target " << target;
        EXPECT_EQ(two_d[m].depth, 0);
        EXPECT_EQ(full[m].depth, 5);  // log2(32)
        kept_2d += two_d[m].kept;
        kept_full += full[m].kept;
        kept_adaptive += adaptive[m].kept;
      }
      // On a mixed matrix, choosing per column beats both fixed choices overall.
      EXPECT_LT(kept_adaptive, std::min(kept_2d, kept_full)) << "target " << target;
    }
  }
}

// The paper's inflation point: a spike is one pixel coefficient but a chain
// of detail coefficients at every level of a full transform; a smooth column
// is the opposite.
TEST(TransformColumnsTest, FullInflatesSpikyColumnsAndShrinksSmoothOnes) {
  BakeParams p = SmallJob();
  p.target_error = 0.01;
  const auto two_d = CodeMatrix(WithMode(p, ColumnMode::k2d));
  const auto full = CodeMatrix(WithMode(p, ColumnMode::kFull));
  const auto adaptive = CodeMatrix(WithMode(p, ColumnMode::kAdaptive));
  int spiky = 0, smooth = 0;
  for (size_t m = 0; m < two_d.size(); ++m) {
    if (KindOf(m) == SyntheticKind::kSpiky) {
      ++spiky;
      EXPECT_LE(two_d[m].kept, 3u) << m;
      EXPECT_GT(full[m].kept, 2 * two_d[m].kept) << m;
      EXPECT_EQ(adaptive[m].depth, 0) << m;
    } else if (KindOf(m) == SyntheticKind::kSmooth) {
      ++smooth;
      EXPECT_LT(full[m].kept, two_d[m].kept) << m;
      EXPECT_GT(adaptive[m].depth, 0) << m;
    }
  }
  EXPECT_GT(spiky, 50);
  EXPECT_GT(smooth, 100);
}

// Depth 0 keeps the pixel values themselves, so the kept count can be checked
// by brute force: sort the squared values and drop from the smallest while
// the dropped energy fits target²·E_ref, E_ref = Σ T² / M.
TEST(TransformColumnsTest, TwoDCountMatchesBruteForceBudget) {
  BakeParams p = WithMode(SmallJob(), ColumnMode::k2d);
  p.target_error = 0.02;
  const auto two_d = CodeMatrix(p);
  const auto image = SyntheticMatrix(32, 32);
  double total = 0;
  for (int m = 0; m < 384; ++m)
    for (int i = 0; i < 1024; ++i) total += std::pow(double(image(m, i % 32, i / 32)), 2);
  const double budget = p.target_error * p.target_error * total / 384;
  for (int m = 0; m < 384; ++m) {
    std::vector<double> e;
    for (int i = 0; i < 1024; ++i)
      if (image(m, i % 32, i / 32) != 0) e.push_back(std::pow(double(image(m, i % 32, i / 32)), 2));
    std::sort(e.begin(), e.end());
    size_t dropped = 0;
    double sum = 0;
    while (dropped < e.size() && sum + e[dropped] <= budget) sum += e[dropped++];
    EXPECT_EQ(two_d[m].kept, e.size() - dropped) << "column " << m;
    EXPECT_LE(two_d[m].dropped_energy, budget);
  }
}

TEST(TransformColumnsTest, EmptyColumnsKeepNothing) {
  const auto adaptive = CodeMatrix(SmallJob());
  int empty = 0;
  for (size_t m = 0; m < adaptive.size(); ++m) {
    if (KindOf(m) != SyntheticKind::kEmpty) continue;
    ++empty;
    EXPECT_EQ(adaptive[m].kept, 0u);
    EXPECT_EQ(adaptive[m].energy, 0);
    EXPECT_EQ(adaptive[m].depth, 0);
  }
  EXPECT_EQ(empty, 24);
}

// --column-terms K: at most K per column, and adaptive picks the depth that
// drops the least energy, so it never drops more than 2D or full.
TEST(TransformColumnsTest, FixedTermsPicksLeastDroppedEnergy) {
  BakeParams p = SmallJob();
  p.column_terms = 6;
  const auto two_d = CodeMatrix(WithMode(p, ColumnMode::k2d));
  const auto full = CodeMatrix(WithMode(p, ColumnMode::kFull));
  const auto adaptive = CodeMatrix(WithMode(p, ColumnMode::kAdaptive));
  for (size_t m = 0; m < adaptive.size(); ++m) {
    EXPECT_LE(adaptive[m].kept, 6u);
    const double best = std::min(two_d[m].dropped_energy, full[m].dropped_energy);
    EXPECT_LE(adaptive[m].dropped_energy, best * (1 + 1e-9) + 1e-12) << "column " << m;
    if (KindOf(m) == SyntheticKind::kSpiky) {
      EXPECT_EQ(two_d[m].kept, 3u);  // only 3 nonzero pixels: zeros are never kept
      EXPECT_EQ(two_d[m].dropped_energy, 0);
    }
  }
}

TEST(TransformColumnsTest, RetryRewritesTheSameBytes) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(32, 32));
  GroupStats stats;
  ASSERT_TRUE(TransformColumns(*ctx, store, 1, &stats).ok());
  const auto first = column_testing::ReadTree(GroupResultDir(store));
  ASSERT_TRUE(TransformColumns(*ctx, store, 1, &stats).ok());
  EXPECT_EQ(column_testing::ReadTree(GroupResultDir(store)), first);
  EXPECT_EQ(stats.columns, 100);
  EXPECT_EQ(stats.staging_bytes, 4u * 100 * 256 * 4);  // 4 tiles × one [100, 256] chunk
  EXPECT_GT(stats.kept, 0u);
}

TEST(TransformColumnsTest, ErrorsNameTheProblem) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  absl::Status s = TransformColumns(*ctx, store, 0, nullptr);
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << s;
  EXPECT_THAT(s.message(), ::testing::HasSubstr("staging"));

  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(32, 32));
  for (int bad : {-1, 4}) {
    s = TransformColumns(*ctx, store, bad, nullptr);
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument) << s;
    EXPECT_THAT(s.message(), ::testing::HasSubstr("group"));
  }
  // A tile whose energy was never written has not been baked: refuse to read zeros.
  std::filesystem::remove(store::Path(store, store::kStagingTileEnergy) / "2");
  s = TransformColumns(*ctx, store, 0, nullptr);
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << s;
  EXPECT_THAT(s.message(), ::testing::HasSubstr("tile 2"));
  EXPECT_FALSE(std::filesystem::exists(GroupResultPath(store, 0)));

  // Staging of another plan (other chunking) is refused, not misread.
  BakeParams other = SmallJob();
  other.column_group = 64;
  auto other_ctx = MakeContext(other);
  s = TransformColumns(*other_ctx, store, 0, nullptr);
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << s;
  EXPECT_THAT(s.message(), ::testing::HasSubstr("chunking"));
}

}  // namespace
}  // namespace wavebake
