// FINALIZE and the store reader against the staged matrix they came from:
// decoding and inverse-transforming a column gives back the staged column
// within the error target plus the quantizer's bound (DESIGN.md §1), the bit
// count is the fewest meeting half the target, and the manifest adds up.
#include "worker/columns/finalize.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/bake/finalize_shards.h"
#include "core/columns/column_coding.h"
#include "core/columns/quantizer.h"
#include "core/wavelets/subband.h"
#include "core/wavelets/wavelet2d.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "storage/zarr/zarr_array.h"
#include "tests/worker/column_test_support.h"
#include "worker/columns/finalize_parts.h"
#include "worker/columns/group_result.h"
#include "worker/columns/shard_plan.h"
#include "worker/columns/store_manifest.h"
#include "worker/columns/transform_columns.h"

namespace wavebake {
namespace {

using column_testing::MakeContext;
using column_testing::ReadTree;
using column_testing::ScratchDir;
using column_testing::SyntheticMatrix;
using column_testing::TransformAll;
using column_testing::WriteSyntheticStaging;

constexpr int kW = 32, kH = 32, kColumns = 384;

BakeParams SmallJob() {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 1;
  p.tile_size = 16;
  p.column_group = 100;
  return p;
}

// Σ T² / M of the synthetic matrix, computed here from its definition.
double MatrixEnergy() {
  const auto image = SyntheticMatrix(kW, kH);
  double total = 0;
  for (int m = 0; m < kColumns; ++m)
    for (int i = 0; i < kW * kH; ++i) total += std::pow(double(image(m, i % kW, i / kW)), 2);
  return total / kColumns;
}

struct Baked {
  ScratchDir dir;
  std::filesystem::path store;
  std::unique_ptr<BakeContext> ctx;
};

// Synthetic staging → every group → FINALIZE.
std::unique_ptr<Baked> Bake(const BakeParams& params, bool keep_staging = false) {
  auto b = std::make_unique<Baked>();
  b->store = b->dir.path() / "out.wbk";
  b->ctx = MakeContext(params);
  WriteSyntheticStaging(b->ctx->plan, b->store, SyntheticMatrix(kW, kH));
  TransformAll(*b->ctx, b->store);
  const absl::Status s = Finalize(*b->ctx, b->store, {.keep_staging = keep_staging});
  EXPECT_TRUE(s.ok()) << s;
  return b;
}

// The staged column m and its reconstruction from the decoded store.
std::vector<float> Staged(int m) {
  const auto image = SyntheticMatrix(kW, kH);
  std::vector<float> col(kW * kH);
  for (int i = 0; i < kW * kH; ++i) col[i] = image(m, i % kW, i / kW);
  return col;
}

std::vector<float> Reconstruct(const CompressedColumns& t, WaveletFilter f, int m) {
  std::vector<float> img(kW * kH, 0.0f);
  for (int64_t k = t.indptr[m]; k < t.indptr[m + 1]; ++k) img[t.indices[k]] = t.values[k];
  Inverse2d(f, img, kW, kH, t.depth[m]);
  return img;
}

std::vector<float> ReadScales(const std::filesystem::path& store) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kScale));
  EXPECT_TRUE(a.ok()) << a.status();
  absl::StatusOr<std::vector<float>> v = a->ReadAll<float>();
  EXPECT_TRUE(v.ok()) << v.status();
  return v.ok() ? *v : std::vector<float>{};
}

// Haar is orthonormal: the image error² is the dropped energy plus the
// coefficient errors², each at most QuantizationBound (core/columns/quantizer.h).
void ExpectWithinTargetPlusQuantization(const BakeParams& p) {
  auto b = Bake(p);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(b->store);
  ASSERT_TRUE(info.ok()) << info.status();
  absl::StatusOr<CompressedColumns> t = ReadTransport(b->store);
  ASSERT_TRUE(t.ok()) << t.status();
  const std::vector<float> scales = ReadScales(b->store);
  const double matrix_energy = MatrixEnergy();
  int checked = 0;
  for (int m = 0; m < kColumns; ++m) {
    const std::vector<float> staged = Staged(m);
    const std::vector<float> recon = Reconstruct(*t, WaveletFilter::kHaar, m);
    double err2 = 0, energy = 0, quant2 = 0;
    for (int i = 0; i < kW * kH; ++i) {
      err2 += std::pow(double(recon[i]) - staged[i], 2);
      energy += std::pow(double(staged[i]), 2);
    }
    for (int64_t k = t->indptr[m]; k < t->indptr[m + 1]; ++k) {
      const uint32_t pos = t->indices[k];
      const int level = SubbandAt(pos % kW, pos / kW, kW, kH, t->depth[m]).level;
      quant2 += std::pow(QuantizationBound(scales[m], level, p.level_scaling), 2);
    }
    const double reference = p.error_scope == ErrorScope::kColumn ? energy : matrix_energy;
    const double bound = std::sqrt(p.target_error * p.target_error * reference + quant2);
    // Slack: float rounding of the inverse transform.
    EXPECT_LE(std::sqrt(err2), bound * (1 + 1e-5) + 1e-6 * std::sqrt(energy)) << "column " << m;
    checked += energy > 0;
  }
  EXPECT_EQ(checked, kColumns - 24);  // every column but the empty ones
}

TEST(FinalizeTest, ReconstructsWithinTargetPlusQuantizationMatrixScope) {
  for (LevelScaling s : {LevelScaling::kUniform, LevelScaling::kPaper}) {
    for (double target : {0.003, 0.03}) {
      BakeParams p = SmallJob();
      p.target_error = target;
      p.level_scaling = s;
      ExpectWithinTargetPlusQuantization(p);
    }
  }
}

TEST(FinalizeTest, ReconstructsWithinTargetPlusQuantizationColumnScope) {
  BakeParams p = SmallJob();
  p.error_scope = ErrorScope::kColumn;
  ExpectWithinTargetPlusQuantization(p);  // uniform auto: each column's own step
  p.bits = 10;
  ExpectWithinTargetPlusQuantization(p);
}

// Keeping every coefficient of a full transform and quantizing at 16 bits is
// perfect reconstruction up to quantization, for the biorthogonal filters too
// (their synthesis operators are bounded; 4 is a loose bound on their norm).
TEST(FinalizeTest, BiorthogonalFiltersReconstructWhenEverythingIsKept) {
  for (WaveletFilter f : {WaveletFilter::kLeGall53, WaveletFilter::kCdf97}) {
    BakeParams p = SmallJob();
    p.column_filter = f;
    p.column_mode = ColumnMode::kFull;
    p.column_terms = kW * kH;
    p.bits = 16;
    auto b = Bake(p);
    absl::StatusOr<CompressedColumns> t = ReadTransport(b->store);
    ASSERT_TRUE(t.ok()) << t.status();
    const std::vector<float> scales = ReadScales(b->store);
    for (int m : {0, 1, 2, 5, 100, 383}) {
      const std::vector<float> staged = Staged(m), recon = Reconstruct(*t, f, m);
      double err2 = 0, quant2 = 0;
      for (int i = 0; i < kW * kH; ++i) err2 += std::pow(double(recon[i]) - staged[i], 2);
      for (int64_t k = t->indptr[m]; k < t->indptr[m + 1]; ++k) {
        const uint32_t pos = t->indices[k];
        quant2 +=
            std::pow(QuantizationBound(scales[m], SubbandAt(pos % kW, pos / kW, kW, kH, 5).level,
                                       p.level_scaling, MaxQuantCode(16)),
                     2);
      }
      EXPECT_EQ(t->depth[m], 5);
      EXPECT_LE(std::sqrt(err2), 4 * std::sqrt(quant2) + 1e-6)
          << "filter " << int(f) << " column " << m;
    }
  }
}

// The paper's rule (--level-scaling paper): Δ_b = max_i |v_i·2^l_i| / Q_b and
// the expected subtractive-dither error energy Σ_i (Δ_b 2^−l_i)²/12, here
// per unit 1/Q_b², recomputed from the kept coefficients in staging, one
// entry per column in column order.
std::vector<double> DitherUnits(const Baked& b) {
  std::vector<double> units;
  for (int g = 0; g < b.ctx->plan.groups; ++g) {
    absl::StatusOr<GroupResult> r = ReadGroupResult(b.store, g);
    EXPECT_TRUE(r.ok()) << r.status();
    if (!r.ok()) return units;
    size_t at = 0;
    for (const GroupColumn& c : r->columns) {
      double scale = 0, unit = 0;
      for (size_t k = at; k < at + c.kept; ++k) {
        const uint32_t pos = r->positions[k];
        const int l = SubbandAt(pos % kW, pos / kW, kW, kH, c.depth).level;
        scale = std::max(scale, std::fabs(std::ldexp(double(r->values[k]), l)));
      }
      for (size_t k = at; k < at + c.kept; ++k) {
        const uint32_t pos = r->positions[k];
        const int l = SubbandAt(pos % kW, pos / kW, kW, kH, c.depth).level;
        unit += std::pow(std::ldexp(scale, -l), 2) / 12;
      }
      at += c.kept;
      units.push_back(unit);
    }
  }
  return units;
}

double ExpectedDitherEnergy(double unit, int bits) {
  return unit / std::pow(std::ldexp(1.0, bits - 1) - 1, 2);
}

// --bits auto, matrix scope: with the chosen b the summed expected dither
// energy of all columns is within (target/2)²·(M·E_mean), and with b − 1 it
// is not.
TEST(FinalizeTest, BitsAutoIsTheFewestMeetingHalfTheMatrixTarget) {
  BakeParams p = SmallJob();
  p.target_error = 0.01;
  p.level_scaling = LevelScaling::kPaper;
  auto b = Bake(p, /*keep_staging=*/true);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(b->store);
  ASSERT_TRUE(info.ok()) << info.status();
  const int bits = info->bits;
  EXPECT_EQ(info->attrs["bits_needed"], bits);
  EXPECT_TRUE(info->attrs["bits_auto"].get<bool>());
  const double allowed = 0.25 * p.target_error * p.target_error * MatrixEnergy() * kColumns;
  double total = 0;
  for (double u : DitherUnits(*b)) total += u;
  EXPECT_LE(ExpectedDitherEnergy(total, bits), allowed * (1 + 1e-6));
  ASSERT_GT(bits, 2);
  EXPECT_GT(ExpectedDitherEnergy(total, bits - 1), allowed * (1 - 1e-6));
  EXPECT_LE(bits, info->attrs["max_column_bits"].get<int>());
  std::cout << "bits auto at target 1%: " << bits << " (largest column need "
            << info->attrs["max_column_bits"] << ")\n";
}

// --bits auto, column scope: every column's own expected dither energy is
// within (target/2)² of its own energy, and with b − 1 some column's is not.
TEST(FinalizeTest, BitsAutoColumnScopeMeetsEveryColumn) {
  BakeParams p = SmallJob();
  p.target_error = 0.01;
  p.error_scope = ErrorScope::kColumn;
  p.level_scaling = LevelScaling::kPaper;
  auto b = Bake(p, /*keep_staging=*/true);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(b->store);
  ASSERT_TRUE(info.ok()) << info.status();
  const int bits = info->bits;
  const auto image = SyntheticMatrix(kW, kH);
  const std::vector<double> units = DitherUnits(*b);
  ASSERT_EQ(units.size(), static_cast<size_t>(kColumns));
  bool tight = false;
  for (int m = 0; m < kColumns; ++m) {
    double energy = 0;
    for (int i = 0; i < kW * kH; ++i) energy += std::pow(double(image(m, i % kW, i / kW)), 2);
    const double allowed = 0.25 * p.target_error * p.target_error * energy;
    EXPECT_LE(ExpectedDitherEnergy(units[m], bits), allowed * (1 + 1e-6)) << "column " << m;
    tight |= ExpectedDitherEnergy(units[m], bits - 1) > allowed * (1 - 1e-6);
  }
  EXPECT_TRUE(tight) << bits << " bits is more than the column scope needs";
}

// --bits auto, uniform scaling (the default): one matrix-wide step Δ whose
// expected dither energy Σ n_c·Δ²/12 uses the quantization half budget
// (t/2)²·Σ E_ref. Checked on the decoded store against the unquantized kept
// values left in staging (Haar: every weight is 1), not on FINALIZE's own
// bookkeeping. The achieved energy is a sum of n independent (uniform
// error)² terms of variance Δ⁴/180 each, so it lands within a few σ of the
// budget: neither over it nor far under it (an unspent budget is wasted bits).
TEST(FinalizeTest, UniformStepSpendsTheQuantizationHalfBudget) {
  BakeParams p = SmallJob();
  p.target_error = 0.01;
  auto b = Bake(p, /*keep_staging=*/true);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(b->store);
  ASSERT_TRUE(info.ok()) << info.status();
  absl::StatusOr<CompressedColumns> t = ReadTransport(b->store);
  ASSERT_TRUE(t.ok()) << t.status();
  const std::vector<float> scales = ReadScales(b->store);
  const double step = info->attrs["stats"]["quantization"]["step"].get<double>();
  ASSERT_GT(step, 0);
  EXPECT_EQ(info->attrs["stats"]["quantization"]["overflow_columns"], 0);
  double achieved = 0, variance = 0;
  int64_t k = 0;
  for (int g = 0; g < b->ctx->plan.groups; ++g) {
    absl::StatusOr<GroupResult> r = ReadGroupResult(b->store, g);
    ASSERT_TRUE(r.ok()) << r.status();
    for (size_t i = 0; i < r->values.size(); ++i, ++k) {
      ASSERT_EQ(t->indices[k], r->positions[i]);
      achieved += std::pow(double(t->values[k]) - r->values[i], 2);
      variance += std::pow(step, 4) / 180;
    }
  }
  ASSERT_EQ(k, t->indptr.back());
  for (int m = 0; m < kColumns; ++m) {
    if (t->indptr[m + 1] > t->indptr[m]) {
      EXPECT_EQ(scales[m], float(step)) << "column " << m;
    }
  }
  const double budget = 0.25 * p.target_error * p.target_error * MatrixEnergy() * kColumns;
  EXPECT_LE(achieved, budget + 5 * std::sqrt(variance));
  EXPECT_GE(achieved, budget - 5 * std::sqrt(variance));
  std::cout << "uniform step " << step << ": achieved/budget " << achieved / budget << " (σ "
            << std::sqrt(variance) / budget << ")\n";
}

TEST(FinalizeTest, ManifestAndStatsAddUp) {
  BakeParams p = SmallJob();
  p.target_error = 0.01;
  auto b = Bake(p);
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(b->store);
  ASSERT_TRUE(info.ok()) << info.status();
  const nlohmann::json& a = info->attrs;
  EXPECT_EQ(a["format"], "wavebake/2");
  EXPECT_EQ(a["level_scaling"], "uniform");
  EXPECT_EQ(info->scene_spec, "builtin:furnace");
  EXPECT_EQ(info->scene_hash, b->ctx->scene_hash);
  EXPECT_EQ(info->width, kW);
  EXPECT_EQ(info->height, kH);
  EXPECT_EQ(info->light_res, 8);
  EXPECT_EQ(info->columns, kColumns);
  EXPECT_EQ(info->params.column_mode, ColumnMode::kAdaptive);
  EXPECT_EQ(info->params.target_error, 0.01);
  EXPECT_EQ(info->params.column_group, 100);
  EXPECT_EQ(a["params"]["bits"], "auto");
  EXPECT_EQ(a["filters"]["column"], "haar");

  absl::StatusOr<CompressedColumns> t = ReadTransport(b->store);
  ASSERT_TRUE(t.ok()) << t.status();
  const nlohmann::json& s = a["stats"];
  EXPECT_EQ(s["nnz"].get<int64_t>(), t->indptr.back());
  int64_t histogram_total = 0;
  for (const auto& n : s["depth_histogram"]) histogram_total += n.get<int64_t>();
  EXPECT_EQ(histogram_total, kColumns);
  for (int d = 0; d <= 5; ++d) {
    int64_t count = 0, by_level = 0;
    for (uint8_t depth : t->depth) count += depth == d;
    for (const auto& level : s["depth_by_row_level"]) by_level += level[d].get<int64_t>();
    EXPECT_EQ(s["depth_histogram"][d].get<int64_t>(), count) << d;
    EXPECT_EQ(by_level, count) << d;
  }
  ASSERT_EQ(s["depth_by_row_level"].size(), 4u);  // row levels 0..3 of an 8×8 face
  // 6 faces × 4^l columns at row level l ≥ 1 (6 × 3·4^(l−1)), 6 at level 0.
  const int per_level[4] = {6, 18, 72, 288};
  for (int l = 0; l < 4; ++l) {
    int64_t n = 0;
    for (const auto& c : s["depth_by_row_level"][l]) n += c.get<int64_t>();
    EXPECT_EQ(n, per_level[l]) << "row level " << l;
  }
  const int64_t samples = b->ctx->samples.size();
  EXPECT_EQ(s["bytes"]["raw_float32"].get<int64_t>(), samples * kColumns * 4);
  EXPECT_GT(s["bytes"]["transport"].get<int64_t>(), 0);
  // Dropped ≤ t²·E_ref per column and each dither error ≤ Δ/2, i.e. ≤ 3× its
  // expected Δ²/12, whose sum bits auto keeps ≤ (t/2)²·Σ E_ref: the matrix
  // error ≤ t·sqrt(1 + 3/4).
  EXPECT_LE(s["matrix_rel_rms"].get<double>(), 0.01 * std::sqrt(1.75) * (1 + 1e-6));
  EXPECT_GT(s["column_error"]["mean"].get<double>(), 0);
  std::cout << "stats: " << s.dump() << "\n";
}

TEST(FinalizeTest, ReadColumnMatchesReadTransport) {
  auto b = Bake(SmallJob());
  absl::StatusOr<CompressedColumns> t = ReadTransport(b->store);
  ASSERT_TRUE(t.ok()) << t.status();
  for (int m : {0, 1, 2, 3, 99, 100, 299, 300, 383}) {
    absl::StatusOr<DecodedColumn> c = ReadColumn(b->store, m);
    ASSERT_TRUE(c.ok()) << c.status();
    EXPECT_EQ(c->depth, t->depth[m]);
    const std::vector<uint32_t> positions(t->indices.begin() + t->indptr[m],
                                          t->indices.begin() + t->indptr[m + 1]);
    const std::vector<float> values(t->values.begin() + t->indptr[m],
                                    t->values.begin() + t->indptr[m + 1]);
    EXPECT_EQ(c->positions, positions) << m;
    EXPECT_EQ(c->values, values) << m;
  }
  EXPECT_EQ(ReadColumn(b->store, kColumns).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(ReadColumn(b->store, -1).status().message(), ::testing::HasSubstr("column"));
}

TEST(FinalizeTest, DropsStagingAndRetriesAreNoOps) {
  auto b = Bake(SmallJob());
  EXPECT_FALSE(std::filesystem::exists(b->store / "staging"));
  EXPECT_FALSE(std::filesystem::exists(b->store / ".staging.removing"));
  const auto before = ReadTree(b->store);
  const absl::Status s = Finalize(*b->ctx, b->store, {});
  EXPECT_TRUE(s.ok()) << s;
  EXPECT_EQ(ReadTree(b->store), before);
}

// A worker killed while writing the store's .zgroup (as a tile task does)
// leaves its temp file; the published store must not carry it.
TEST(FinalizeTest, PublishedStoreHoldsNoAbandonedTempFile) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(kW, kH));
  std::ofstream(store / "..zgroup.4242.00000000deadbeef.partial") << "{\"zarr_";
  TransformAll(*ctx, store);
  const absl::Status s = Finalize(*ctx, store, {});
  ASSERT_TRUE(s.ok()) << s;
  EXPECT_FALSE(std::filesystem::exists(store / "..zgroup.4242.00000000deadbeef.partial"));
}

// Bytes of the files under `dir` as the filesystem reports them: the
// oracle for stats.bytes, counted here without the code under test.
uint64_t FileBytes(const std::filesystem::path& dir) {
  uint64_t total = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) total += e.file_size();
  return total;
}

// A stale FINALIZE worker (its lease expired, it resumed while its successor
// finalizes) writes temp files into the arrays; stats.bytes must count only
// the store's own files, which are all that is left once it is published.
TEST(FinalizeTest, StatsBytesCountOnlyTheStoresOwnFiles) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(kW, kH));
  TransformAll(*ctx, store);
  const std::filesystem::path data = store::Path(store, store::kData);
  std::filesystem::create_directories(data);
  const std::filesystem::path stray = data / ".0.4242.00000000deadbeef.partial";
  std::ofstream(stray) << std::string(100000, 'x');
  const absl::Status s = Finalize(*ctx, store, {});
  ASSERT_TRUE(s.ok()) << s;
  EXPECT_FALSE(std::filesystem::exists(stray));
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(store);
  ASSERT_TRUE(info.ok()) << info.status();
  const nlohmann::json& bytes = info->attrs["stats"]["bytes"];
  EXPECT_EQ(bytes["arrays"][store::kData].get<uint64_t>(), FileBytes(data));
  uint64_t transport = 0;
  for (const char* name :
       {store::kIndptr, store::kIndices, store::kData, store::kDepth, store::kScale})
    transport += FileBytes(store::Path(store, name));
  EXPECT_EQ(bytes["transport"].get<uint64_t>(), transport);
  // One appearing while the sizes are counted is not counted either.
  const uint64_t real = FileBytes(data);
  std::ofstream(stray) << std::string(100000, 'x');
  EXPECT_EQ(DirectoryBytes(data), real);
}

TEST(FinalizeTest, RefusesMissingGroupsAndMissingStaging) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  absl::Status s = Finalize(*ctx, store, {});
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << s;
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(kW, kH));
  TransformAll(*ctx, store, {0, 1, 3});
  s = Finalize(*ctx, store, {});
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition) << s;
  EXPECT_THAT(s.message(), ::testing::HasSubstr("group 2"));
  EXPECT_FALSE(std::filesystem::exists(store / ".zattrs"));
}

// A cancelled job's FINALIZE stops between groups (a large store's would
// otherwise outlast the 5 s an interrupted bake may take), writing no
// manifest; run again without the flag it finishes the same store.
TEST(FinalizeTest, StopsWhenCancelledAndFinishesWhenRunAgain) {
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(SmallJob());
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(kW, kH));
  TransformAll(*ctx, store);
  const std::atomic<bool> cancel{true};
  absl::Status s = Finalize(*ctx, store, {.keep_staging = false, .cancel = &cancel});
  EXPECT_EQ(s.code(), absl::StatusCode::kCancelled) << s;
  EXPECT_FALSE(std::filesystem::exists(store / ".zattrs"));
  EXPECT_TRUE(std::filesystem::exists(store / "staging"));
  s = Finalize(*ctx, store, {});
  ASSERT_TRUE(s.ok()) << s;
  EXPECT_EQ(ReadTree(store), ReadTree(Bake(SmallJob())->store));
}

// FINALIZE as tasks (core/bake/finalize_shards.h): 384 columns in 4 groups, so
// 4 shards; the chunks of indices and data each belong to the shard holding
// their first element (a chunk's groups may be several shards'; a
// multi-chunk store is covered by the embedded and Slurm bakes compared with
// main's). Run in a scrambled order with a retry, the last task refused until
// every shard is done, the store is the one-call FINALIZE's byte for byte,
// and indices read back as the groups' positions concatenated (read here
// from the group results, not through FINALIZE).
TEST(FinalizeTest, ShardsInAnyOrderThenTheLastTaskWriteTheOneCallStore) {
  BakeParams p = SmallJob();
  p.column_mode = ColumnMode::kFull;
  p.column_terms = kW * kH;
  p.bits = 16;
  const auto expected = ReadTree(Bake(p)->store);

  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(p);
  ASSERT_EQ(ctx->plan.groups, 4);
  ASSERT_EQ(FinalizeShards(ctx->plan.groups), 4);
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(kW, kH));
  TransformAll(*ctx, store);
  std::vector<uint32_t> positions;
  for (int g = 0; g < ctx->plan.groups; ++g) {
    absl::StatusOr<GroupResult> r = ReadGroupResult(store, g);
    ASSERT_TRUE(r.ok()) << r.status();
    positions.insert(positions.end(), r->positions.begin(), r->positions.end());
  }
  ASSERT_GT(positions.size(), 0u);
  for (int shard : {3, 1, 2}) {
    ASSERT_TRUE(FinalizeShard(*ctx, store, shard, {.threads = 2}).ok());
  }
  absl::Status early = FinalizeStore(*ctx, store, {});
  EXPECT_EQ(early.code(), absl::StatusCode::kFailedPrecondition) << early;
  EXPECT_THAT(early.message(), ::testing::HasSubstr("shard 0"));
  for (int shard : {0, 2}) {
    ASSERT_TRUE(FinalizeShard(*ctx, store, shard, {.threads = 1}).ok());
  }
  EXPECT_EQ(FinalizeShard(*ctx, store, 4, {}).code(), absl::StatusCode::kInvalidArgument);
  ASSERT_TRUE(FinalizeStore(*ctx, store, {}).ok());
  EXPECT_EQ(ReadTree(store), expected);
  absl::StatusOr<ZarrArray> indices = ZarrArray::Open(store / "transport/indices");
  ASSERT_TRUE(indices.ok());
  EXPECT_EQ(indices->ReadAll<uint32_t>().value(), positions);
  // A shard retried after the store is finished has nothing to do.
  EXPECT_TRUE(FinalizeShard(*ctx, store, 1, {}).ok());
  EXPECT_EQ(ReadTree(store), expected);
}

// The shards' plan (worker/columns/shard_plan.h): the first shard keeps it,
// it reads back as worked out from the group results, a file that is not a
// plan of this job is worked out again (and the store still comes out right),
// and a group result written anew removes it.
TEST(FinalizeTest, ShardsShareOnePlanThatANewGroupResultRemoves) {
  const BakeParams p = SmallJob();
  const auto expected = ReadTree(Bake(p)->store);
  ScratchDir dir;
  const auto store = dir.path() / "out.wbk";
  auto ctx = MakeContext(p);
  WriteSyntheticStaging(ctx->plan, store, SyntheticMatrix(kW, kH));
  TransformAll(*ctx, store);
  EXPECT_EQ(ReadShardPlan(store, ctx->plan).status().code(), absl::StatusCode::kNotFound);
  ASSERT_TRUE(FinalizeShard(*ctx, store, 2, {}).ok());
  absl::StatusOr<ShardPlan> kept = ReadShardPlan(store, ctx->plan);
  ASSERT_TRUE(kept.ok()) << kept.status();
  absl::StatusOr<FinalizeScan> scan = ScanGroups(ctx->plan, store, {});
  ASSERT_TRUE(scan.ok());
  const StepPlan steps = PlanFinalizeSteps(*scan, p);
  EXPECT_EQ(kept->group_offsets, scan->group_offsets);
  EXPECT_EQ(kept->steps, steps.steps);
  EXPECT_EQ(kept->max_code, steps.max_code);

  JobPlan other = ctx->plan;
  other.groups += 1;
  const absl::Status mismatched = ReadShardPlan(store, other).status();
  EXPECT_EQ(mismatched.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(mismatched.message(), ::testing::HasSubstr("plan.wbp"));
  std::filesystem::resize_file(ShardPlanPath(store), 10);
  for (int shard = 0; shard < FinalizeShards(ctx->plan.groups); ++shard)
    ASSERT_TRUE(FinalizeShard(*ctx, store, shard, {}).ok());
  ASSERT_TRUE(ReadShardPlan(store, ctx->plan).ok());  // worked out and kept again
  ASSERT_TRUE(FinalizeStore(*ctx, store, {}).ok());
  EXPECT_EQ(ReadTree(store), expected);

  ScratchDir again;
  const auto recoded = again.path() / "out.wbk";
  WriteSyntheticStaging(ctx->plan, recoded, SyntheticMatrix(kW, kH));
  TransformAll(*ctx, recoded);
  ASSERT_TRUE(WriteShardPlan(recoded, *kept).ok());
  ASSERT_TRUE(TransformColumns(*ctx, recoded, 1, nullptr).ok());
  EXPECT_FALSE(std::filesystem::exists(ShardPlanPath(recoded)));
}

}  // namespace
}  // namespace wavebake
