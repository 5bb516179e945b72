// BAKE_TILE against physics, read back through the staging store: the white
// furnace, the disk's analytic occlusion, and the row transform's round trip
// and Parseval identity against TransportRow computed here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "tests/worker/staging_testing.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/row_transform.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

using staging_testing::ContextOrDie;
using staging_testing::ScratchDir;
using staging_testing::StagedTile;
using staging_testing::StagedTileEnergy;

// Σ_m T[s,m] from a staged row without inverting it: a face's scaling
// coefficient, at its texel (0, 0), is (Σ over the face)/N for both row
// filters (tests/worker/row_transform_test.cc).
double PixelSumFromScaling(const std::vector<float>& staged, int n) {
  double sum = 0;
  for (int face = 0; face < 6; ++face) sum += double{staged[face * n * n]} * n;
  return sum;
}

int32_t SampleAt(const BakeContext& ctx, const TileRect& rect, int cell) {
  const int x = rect.x0 + cell % rect.width, y = rect.y0 + cell / rect.width;
  return ctx.samples.grid[y * ctx.samples.width + x];
}

void BakeAllTiles(const BakeContext& ctx, const std::filesystem::path& store,
                  TileStats* stats = nullptr) {
  ASSERT_TRUE(CreateStaging(ctx.plan, store).ok());
  for (int t = 0; t < ctx.plan.tiles(); ++t) ASSERT_TRUE(BakeTile(ctx, store, t, stats).ok()) << t;
}

// White furnace (DESIGN.md §1): nothing occludes the flat ground, so every
// sample's row sums to ∫ cos/π dω = 1 — also at the plane's edge, where the
// whole upper hemisphere is still open. At N=16 K=4 the jittered quadrature's
// error has σ ≤ 0.05 % (tests/core/transport_row_test.cc), far inside 0.5 %.
// column_group 100 leaves the last of 16 groups 36 columns and 64 padding rows.
TEST(BakeTilePhysicsTest, WhiteFurnaceFromStagedRows) {
  BakeParams p;
  p.light_res = 16;
  p.supersample = 4;
  p.layout = "camera:16x16";
  p.tile_size = 8;
  p.column_group = 100;
  const auto ctx = ContextOrDie("builtin:furnace", p);
  ASSERT_NE(ctx, nullptr);
  ScratchDir dir;
  TileStats stats;
  BakeAllTiles(*ctx, dir.path(), &stats);

  const JobPlan& plan = ctx->plan;
  ASSERT_EQ(plan.groups, 16);
  uint64_t samples = 0;
  for (int t = 0; t < plan.tiles(); ++t) {
    const StagedTile tile(dir.path(), plan, t);
    ASSERT_TRUE(tile.ok());
    for (int cell = 0; cell < plan.tile_cells(); ++cell) {
      const std::vector<float> row = tile.Row(cell);
      if (SampleAt(*ctx, plan.Tile(t), cell) < 0) {
        for (float v : row) ASSERT_EQ(v, 0.0f) << "masked cell " << cell << " of tile " << t;
        continue;
      }
      ++samples;
      EXPECT_NEAR(PixelSumFromScaling(row, p.light_res), 1.0, 0.005)
          << "tile " << t << " cell " << cell;
    }
    const std::vector<float>& last = tile.chunk(plan.groups - 1);
    const int used = plan.GroupCount(plan.groups - 1);
    for (size_t i = size_t(used) * plan.tile_cells(); i < last.size(); ++i) {
      ASSERT_EQ(last[i], 0.0f) << "padding of tile " << t;
    }
  }
  EXPECT_GT(samples, 100u);  // the camera sees mostly ground
  EXPECT_EQ(stats.samples, samples);
  EXPECT_EQ(samples, static_cast<uint64_t>(ctx->samples.size()));
}

// An opaque disk of radius r at height h over a ground point blocks the
// cosine-weighted fraction r²/(r²+h²) of its hemisphere (core/scene/builtin_scenes.h),
// so Σ_m T = 1 − r²/(r²+h²) for the sample of ground vertex (32, 32). Only the
// tile holding that vertex is baked. Measured (seed 1): +0.16 % off at N=32,
// +0.37 % at N=16; N=32 keeps a wide margin to the 1 % bound for 0.5 s.
TEST(BakeTilePhysicsTest, DiskOverPlaneMatchesAnalyticOcclusion) {
  BakeParams p;
  p.light_res = 32;
  p.supersample = 4;
  p.layout = "grid";
  p.tile_size = 8;
  const auto ctx = ContextOrDie("builtin:disk-over-plane", p);
  ASSERT_NE(ctx, nullptr);
  const JobPlan& plan = ctx->plan;
  const int c = builtin::kGroundCentreIndex;
  const int32_t id = ctx->samples.grid[c * ctx->samples.width + c];
  ASSERT_GE(id, 0);
  ASSERT_NEAR(Length(ctx->samples.position[id] - builtin::kDiskPlaneCentre), 0, 1e-5f);

  const int tile = (c / plan.tile_h) * plan.tiles_x + c / plan.tile_w;
  const int cell = (c % plan.tile_h) * plan.tile_w + c % plan.tile_w;
  ScratchDir dir;
  ASSERT_TRUE(CreateStaging(plan, dir.path()).ok());
  ASSERT_TRUE(BakeTile(*ctx, dir.path(), tile, nullptr).ok());

  const StagedTile staged(dir.path(), plan, tile);
  ASSERT_TRUE(staged.ok());
  std::vector<float> row = staged.Row(cell);
  const double from_scaling = PixelSumFromScaling(row, p.light_res);
  InverseRowTransform(p.row_filter, p.light_res, row);
  const double from_pixels = std::accumulate(row.begin(), row.end(), 0.0);

  const double r2 = builtin::kDiskRadius * builtin::kDiskRadius;
  const double h2 = builtin::kDiskHeight * builtin::kDiskHeight;
  const double expected = 1 - r2 / (r2 + h2);
  EXPECT_NEAR(from_pixels, expected, 0.01 * expected);
  EXPECT_NEAR(from_scaling, from_pixels, 1e-5);
}

// The staged row, inverse row-transformed, is the pixel-basis row traced here
// independently (by brute force or by refinement, as the job says); the tile
// energy is Σ staged² read back, and — the filters being orthonormal — also
// Σ of the pixel rows' squares (Parseval).
TEST(BakeTilePhysicsTest, StagedRowsInvertToTransportRows) {
  for (auto [f, refine] : {std::pair{WaveletFilter::kHaar, false},
                           {WaveletFilter::kDaub4, false},
                           {WaveletFilter::kHaar, true}}) {
    BakeParams p;
    p.refine = refine;
    p.light_res = 8;
    p.supersample = 4;
    p.layout = "camera:16x16";
    p.tile_size = 8;
    p.row_filter = f;
    const auto ctx = ContextOrDie("builtin:disk-over-plane", p);
    ASSERT_NE(ctx, nullptr);
    ScratchDir dir;
    BakeAllTiles(*ctx, dir.path());

    const JobPlan& plan = ctx->plan;
    int shadowed = 0;
    for (int t = 0; t < plan.tiles(); ++t) {
      const StagedTile tile(dir.path(), plan, t);
      ASSERT_TRUE(tile.ok());
      double staged_energy = 0, pixel_energy = 0;
      for (int cell = 0; cell < plan.tile_cells(); ++cell) {
        std::vector<float> row = tile.Row(cell);
        for (float v : row) staged_energy += double{v} * v;
        const int32_t id = SampleAt(*ctx, plan.Tile(t), cell);
        if (id < 0) continue;
        std::vector<float> pixels(plan.columns);
        if (refine) {
          RefineScratch scratch;
          RefinedTransportRow(ctx->caster, ctx->cubemap, ctx->jitter, *ctx->refine,
                              ctx->samples.position[id], ctx->samples.normal[id], ctx->epsilon,
                              pixels, nullptr, scratch);
        } else {
          TransportRow(ctx->caster, ctx->cubemap, ctx->jitter, ctx->samples.position[id],
                       ctx->samples.normal[id], ctx->epsilon, pixels, nullptr);
        }
        InverseRowTransform(f, p.light_res, row);
        const float peak = *std::max_element(pixels.begin(), pixels.end());
        for (int m = 0; m < plan.columns; ++m) {
          ASSERT_NEAR(row[m], pixels[m], 1e-6f * peak) << "tile " << t << " cell " << cell;
          pixel_energy += double{pixels[m]} * pixels[m];
        }
        shadowed += std::accumulate(pixels.begin(), pixels.end(), 0.0) < 0.95;
      }
      const float energy = StagedTileEnergy(dir.path(), t);
      EXPECT_NEAR(energy, staged_energy, 1e-6 * staged_energy) << "tile " << t;
      EXPECT_NEAR(energy, pixel_energy, 1e-5 * pixel_energy) << "tile " << t;
    }
    EXPECT_GT(shadowed, 0) << "the disk should shadow some samples";
  }
}

}  // namespace
}  // namespace wavebake
