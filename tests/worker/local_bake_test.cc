// The single-process driver end to end (DESIGN.md §2, §5): real BAKE_TILE
// staging through the column stage into a store that is bit-identical
// whatever the threads and task order, passes the white furnace through the
// whole pipeline, and is all or nothing on disk.
#include "worker/local_bake.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

#include "absl/strings/str_cat.h"
#include "core/bake_params_io.h"
#include "core/wavelet2d.h"
#include "storage/store_layout.h"
#include "storage/store_reader.h"
#include "tests/worker/column_test_support.h"
#include "worker/bake_tile.h"
#include "worker/finalize.h"
#include "worker/group_result.h"
#include "worker/publish_store.h"
#include "worker/staging.h"
#include "worker/transform_columns.h"

namespace wavebake {
namespace {

using column_testing::ReadTree;
using column_testing::ScratchDir;
using ::testing::HasSubstr;

// 32×32 camera samples, N = 8 (384 columns), 4 tiles, 4 groups (last padded).
BakeParams SmallJob() {
  BakeParams p;
  p.light_res = 8;
  p.supersample = 1;
  p.layout = "camera:32x32";
  p.tile_size = 16;
  p.column_group = 100;
  return p;
}

constexpr char kScene[] = "builtin:cylinder-bump";

absl::StatusOr<BakeSummary> Bake(const std::filesystem::path& out, int threads,
                                 const BakeParams& p = SmallJob(), const char* scene = kScene) {
  LocalBakeOptions options;
  options.threads = threads;
  return RunLocalBake(scene, p, out, options);
}

// Names in `dir` that are not `keep` (partial or old stores left behind).
std::vector<std::string> Leftovers(const std::filesystem::path& dir, const std::string& keep) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != keep) names.push_back(name);
  }
  return names;
}

TEST(LocalBakeTest, BitIdenticalAcrossThreadsAndShuffledTaskOrder) {
  ScratchDir dir;
  ASSERT_TRUE(Bake(dir.path() / "one.wbk", 1).ok());
  ASSERT_TRUE(Bake(dir.path() / "two.wbk", 2).ok());

  // The tasks driven by hand in a shuffled order, with a retried tile and group.
  const auto manual = dir.path() / "manual.wbk";
  auto ctx = MakeBakeContext(kScene, SmallJob());
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  const JobPlan& plan = (*ctx)->plan;
  std::mt19937 rng(7);
  std::vector<int> tiles(plan.tiles()), groups(plan.groups);
  std::iota(tiles.begin(), tiles.end(), 0);
  std::iota(groups.begin(), groups.end(), 0);
  std::shuffle(tiles.begin(), tiles.end(), rng);
  std::shuffle(groups.begin(), groups.end(), rng);
  tiles.push_back(tiles.front());
  groups.push_back(groups.front());
  ASSERT_TRUE(CreateStaging(plan, manual).ok());
  for (int t : tiles) ASSERT_TRUE(BakeTile(**ctx, manual, t, nullptr).ok());
  for (int g : groups) ASSERT_TRUE(TransformColumns(**ctx, manual, g, nullptr).ok());
  ASSERT_TRUE(Finalize(**ctx, manual, {}).ok());

  const auto one = ReadTree(dir.path() / "one.wbk");
  EXPECT_GT(one.size(), 10u);
  EXPECT_EQ(ReadTree(dir.path() / "two.wbk"), one);
  EXPECT_EQ(ReadTree(manual), one);
}

// L ≡ 1 on builtin:furnace: B = Σ_m T[s,m] = 1 for every sample. With the
// Haar row transform the pixel sum of a face is N × its scaling coefficient
// (column face·N²), so B is six decoded, inverse-column-transformed columns.
TEST(LocalBakeTest, WhiteFurnaceSurvivesTheWholePipeline) {
  ScratchDir dir;
  const auto out = dir.path() / "furnace.wbk";
  BakeParams p = SmallJob();
  p.supersample = 4;
  ASSERT_TRUE(Bake(out, 2, p, "builtin:furnace").ok());
  absl::StatusOr<SampleSet> samples = ReadSamples(out);
  ASSERT_TRUE(samples.ok()) << samples.status();
  std::vector<double> b(32 * 32, 0.0);
  for (int face = 0; face < 6; ++face) {
    absl::StatusOr<DecodedColumn> c = ReadColumn(out, face * 64);
    ASSERT_TRUE(c.ok()) << c.status();
    std::vector<float> img(32 * 32, 0.0f);
    for (size_t k = 0; k < c->positions.size(); ++k) img[c->positions[k]] = c->values[k];
    Inverse2d(WaveletFilter::kHaar, img, 32, 32, c->depth);
    for (int i = 0; i < 32 * 32; ++i) b[i] += 8.0 * img[i];
  }
  double sum2 = 0;
  int n = 0;
  for (int i = 0; i < 32 * 32; ++i) {
    if (samples->grid[i] < 0) continue;
    sum2 += (b[i] - 1) * (b[i] - 1);
    ++n;
  }
  ASSERT_GT(n, 512);
  EXPECT_LT(std::sqrt(sum2 / n), 0.01) << "rms |B − 1| over " << n << " samples";
  std::cout << "white furnace: rms |B - 1| = " << std::sqrt(sum2 / n) << " over " << n
            << " samples\n";
}

TEST(LocalBakeTest, SummaryAndProgressAddUp) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  std::vector<BakeProgress> seen;
  absl::StatusOr<BakeSummary> s =
      RunLocalBake(kScene, SmallJob(), out,
                   {.threads = 2, .progress = [&](const BakeProgress& p) { seen.push_back(p); }});
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ(s->tiles, 4);
  EXPECT_EQ(s->groups, 4);
  EXPECT_GT(s->samples, 0u);
  // supersample 1: at most one ray per (sample, texel); horizon culling skips some.
  EXPECT_GT(s->rays_traced, 0u);
  EXPECT_LE(s->rays_traced, s->samples * 384);
  EXPECT_EQ(s->raw_bytes, s->samples * 384 * 4);
  EXPECT_GE(s->bits, 2);
  // Matrix scope: every column's error is relative to the same mean energy,
  // so their mean ≤ their RMS = the matrix error ≤ t·sqrt(1 + 3/4) (dropped
  // ≤ t², dither ≤ 3× its expected (t/2)² budget). Single columns may exceed
  // it: --bits auto budgets the dither over the whole matrix.
  EXPECT_LE(s->column_error_mean, 0.01 * std::sqrt(1.75) * (1 + 1e-6));
  absl::StatusOr<CompressedColumns> t = ReadTransport(out);
  ASSERT_TRUE(t.ok()) << t.status();
  EXPECT_EQ(s->nnz, t->indptr.back());

  ASSERT_FALSE(seen.empty());
  const std::vector<std::string> phases = {"bake tiles", "transform columns", "finalize"};
  std::vector<std::string> order;
  for (const BakeProgress& p : seen) {
    if (order.empty() || order.back() != p.phase) order.push_back(p.phase);
    EXPECT_LE(p.done, p.total);
  }
  EXPECT_EQ(order, phases);
  EXPECT_EQ(seen.back().done, seen.back().total);
  EXPECT_EQ(seen.back().rays, s->rays_traced);
  EXPECT_TRUE(
      std::is_sorted(seen.begin(), seen.end(),
                     [](const BakeProgress& a, const BakeProgress& b) { return a.rays < b.rays; }));
  EXPECT_THAT(Leftovers(dir.path(), "out.wbk"), ::testing::IsEmpty());
}

TEST(LocalBakeTest, InvalidParametersLeaveNoOutput) {
  ScratchDir dir;
  const auto out = dir.path() / "bad.wbk";
  struct Case {
    const char* field;
    std::function<void(BakeParams&)> spoil;
  };
  const Case cases[] = {
      {"bits", [](BakeParams& p) { p.bits = 1; }},
      {"bits", [](BakeParams& p) { p.bits = 17; }},
      {"target_error", [](BakeParams& p) { p.target_error = -0.01; }},
      {"column_filter", [](BakeParams& p) { p.column_filter = WaveletFilter::kDaub4; }},
      {"light_res", [](BakeParams& p) { p.light_res = 12; }},
      {"layout", [](BakeParams& p) { p.layout = "spiral"; }},
  };
  for (const Case& c : cases) {
    BakeParams p = SmallJob();
    c.spoil(p);
    absl::StatusOr<BakeSummary> s = Bake(out, 1, p);
    EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument) << c.field;
    EXPECT_THAT(s.status().message(), HasSubstr(c.field));
    EXPECT_THAT(Leftovers(dir.path(), ""), ::testing::IsEmpty()) << c.field;
  }
  // Unknown names are refused where strings become params (CLI, RPC, store).
  EXPECT_THAT(ParseWaveletFilter("db8").status().message(), HasSubstr("filter"));
  EXPECT_THAT(ParseColumnMode("fast").status().message(), HasSubstr("column_mode"));
  absl::StatusOr<BakeSummary> s = Bake(out, 1, SmallJob(), "no/such/scene.obj");
  EXPECT_FALSE(s.ok());
  EXPECT_THAT(Leftovers(dir.path(), ""), ::testing::IsEmpty());
}

TEST(LocalBakeTest, RefusesToOverwriteWhatIsNotAStore) {
  ScratchDir dir;
  const auto out = dir.path() / "precious.txt";
  { std::ofstream(out) << "keep me"; }
  absl::StatusOr<BakeSummary> s = Bake(out, 1);
  EXPECT_EQ(s.status().code(), absl::StatusCode::kAlreadyExists) << s.status();
  EXPECT_THAT(s.status().message(), HasSubstr("out"));
  EXPECT_EQ(ReadTree(dir.path()).at("precious.txt"), "keep me");
  EXPECT_THAT(Leftovers(dir.path(), "precious.txt"), ::testing::IsEmpty());
  s = Bake(dir.path() / "no_dir" / "x.wbk", 1);
  EXPECT_EQ(s.status().code(), absl::StatusCode::kInvalidArgument) << s.status();
}

TEST(LocalBakeTest, ReplacesAnExistingStoreWhole) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  ASSERT_TRUE(Bake(out, 2).ok());
  BakeParams p = SmallJob();
  p.column_mode = ColumnMode::k2d;
  p.bits = 9;
  ASSERT_TRUE(Bake(out, 2, p).ok());
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(out);
  ASSERT_TRUE(info.ok()) << info.status();
  EXPECT_EQ(info->params.column_mode, ColumnMode::k2d);
  EXPECT_EQ(info->bits, 9);
  EXPECT_THAT(Leftovers(dir.path(), "out.wbk"), ::testing::IsEmpty());
  // Same bytes as a fresh bake of the new params: nothing of the old store remains.
  ASSERT_TRUE(Bake(dir.path() / "fresh.wbk", 1, p).ok());
  EXPECT_EQ(ReadTree(out), ReadTree(dir.path() / "fresh.wbk"));
}

// Replacing a store deletes it: a file of the user's inside used to go with
// it without a word. Now the replacement is refused naming the file, which
// stays; a store with its kept staging (--keep-staging) is still replaced.
TEST(LocalBakeTest, RefusesToReplaceAStoreHoldingAUsersFile) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  LocalBakeOptions keep;
  keep.threads = 2;
  keep.keep_staging = true;
  ASSERT_TRUE(RunLocalBake(kScene, SmallJob(), out, keep).ok());
  ASSERT_TRUE(std::filesystem::exists(out / "staging" / "groups"));
  ASSERT_TRUE(Bake(out, 2).ok()) << "kept staging is the bake's own";
  for (const std::filesystem::path& foreign :
       {out / "notes.txt", out / "transport" / "data" / "notes.txt", out / "mine" / "x.bin"}) {
    std::filesystem::create_directories(foreign.parent_path());
    { std::ofstream(foreign) << "keep me"; }
    absl::StatusOr<BakeSummary> s = Bake(out, 2);
    EXPECT_EQ(s.status().code(), absl::StatusCode::kAlreadyExists) << s.status();
    const bool in_own_dir = foreign.parent_path().filename() == "mine";  // not a Zarr node
    EXPECT_THAT(s.status().message(),
                HasSubstr((in_own_dir ? foreign.parent_path() : foreign).string() + ","));
    EXPECT_EQ(ReadTree(dir.path()).at(std::filesystem::relative(foreign, dir.path()).string()),
              "keep me");
    EXPECT_THAT(Leftovers(dir.path(), "out.wbk"), ::testing::IsEmpty());
    std::filesystem::remove_all(foreign);
    if (in_own_dir) std::filesystem::remove(foreign.parent_path());
  }
}

// --out through a symbolic link: the store goes to the link's target (it used
// to fail with "INTERNAL: rename … Not a directory"); given a link, the
// publishing step refuses it clearly.
TEST(LocalBakeTest, ASymlinkedOutputIsResolvedToItsTarget) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "disk");
  const auto target = dir.path() / "disk" / "real.wbk";
  const auto link = dir.path() / "out.wbk";
  std::filesystem::create_symlink("disk/real.wbk", link);  // dangling: nothing baked yet
  absl::StatusOr<std::filesystem::path> resolved = ResolveOutputPath(link);
  ASSERT_TRUE(resolved.ok()) << resolved.status();
  EXPECT_EQ(*resolved, dir.path() / "disk/real.wbk");
  ASSERT_TRUE(Bake(*resolved, 2).ok());
  ASSERT_TRUE(ReadStoreInfo(link).ok()) << "readable through the link";
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  ASSERT_TRUE(Bake(*ResolveOutputPath(link), 2).ok()) << "replaced through the link";
  EXPECT_TRUE(std::filesystem::is_symlink(link));

  const absl::Status refused = CheckOutputPath(link);
  EXPECT_EQ(refused.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(refused.message(), HasSubstr("symbolic link"));
  EXPECT_EQ(Bake(link, 1).status().code(), absl::StatusCode::kInvalidArgument);
  std::filesystem::create_symlink("loop", dir.path() / "loop");
  EXPECT_THAT(ResolveOutputPath(dir.path() / "loop").status().message(),
              HasSubstr("too many levels"));
}

// A failure midway (here: the group results cannot be written) removes the
// partial store and leaves an existing store untouched.
TEST(LocalBakeTest, FailureMidwayLeavesNothingBehind) {
  ScratchDir dir;
  const auto out = dir.path() / "out.wbk";
  ASSERT_TRUE(Bake(out, 1).ok());
  const auto before = ReadTree(out);
  const auto partial = std::filesystem::path(out.string() + absl::StrCat(".partial-", ::getpid()));
  bool sabotaged = false;
  auto sabotage = [&](const BakeProgress& p) {
    if (p.phase != "transform columns" || sabotaged) return;
    std::ofstream(partial / "staging" / "groups") << "not a directory";
    sabotaged = true;
  };
  absl::StatusOr<BakeSummary> s =
      RunLocalBake(kScene, SmallJob(), out, {.threads = 2, .progress = sabotage});
  EXPECT_TRUE(sabotaged);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(ReadTree(out), before);
  EXPECT_THAT(Leftovers(dir.path(), "out.wbk"), ::testing::IsEmpty());
}

}  // namespace
}  // namespace wavebake
