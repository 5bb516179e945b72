// The dense staged T relit (driver/relight/staged_relight.h) is the dense retrace of
// runtime/reference/dense_trace.h — another implementation, in the pixel basis — when
// the bake traced by brute force; with refinement it differs only by what
// refinement changes (the exact integral), a fraction of a percent.
#include "driver/relight/staged_relight.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/directions/cubemap.h"
#include "runtime/env/env_map.h"
#include "runtime/env/env_resample.h"
#include "runtime/reference/dense_trace.h"
#include "runtime/reference/eval.h"
#include "tests/testing/scratch_dir.h"
#include "worker/tiles/recode.h"

namespace wavebake::driver {
namespace {

TEST(StagedRelightTest, EqualsTheDenseRetraceOfTheSameRows) {
  for (bool refine : {false, true}) {
    BakeParams p;
    p.light_res = 16;
    p.layout = "camera:32x32";
    p.tile_size = 16;
    p.refine = refine;
    absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext("builtin:cubes-wall", p);
    ASSERT_TRUE(ctx.ok()) << ctx.status();
    test_support::ScratchDir dir;
    ASSERT_TRUE(TraceStaging(**ctx, dir.path() / "trace", {.threads = 2}).ok());
    absl::StatusOr<EnvMap> env = LoadEnvMap(WB_SHARED_DATA "/probes/grace.hdr");
    ASSERT_TRUE(env.ok());
    const std::vector<float> cube = ResampleToCubemap(*env, Cubemap(16));
    absl::StatusOr<std::vector<float>> staged = RelightStaging(**ctx, dir.path() / "trace", cube);
    ASSERT_TRUE(staged.ok()) << staged.status();
    absl::StatusOr<DenseTraceResult> dense = TraceDenseRelight(
        (*ctx)->caster, (*ctx)->samples, cube, {16, p.supersample, p.seed, (*ctx)->epsilon});
    ASSERT_TRUE(dense.ok());
    ASSERT_EQ(staged->size(), dense->rgb.size());
    int masked = 0;
    for (size_t i = 0; i < staged->size(); ++i) {
      ASSERT_EQ(std::isnan((*staged)[i]), std::isnan(dense->rgb[i])) << i;
      masked += std::isnan((*staged)[i]);
    }
    EXPECT_GT(masked, 0);
    const double error = CompareToReference(*staged, dense->rgb).rel_rms;
    if (!refine) {
      EXPECT_LT(error, 1e-5);
    } else {
      EXPECT_GT(error, 1e-6);  // not the same rows
      EXPECT_LT(error, 5e-3);
    }
  }
}

}  // namespace
}  // namespace wavebake::driver
