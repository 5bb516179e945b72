// The path-traced reference with diffuse bounces (runtime/reference/path_reference.h)
// against the spherical cavity's closed form (tests/testing/bowl_scene.h)
// and, with no bounce, against the direct reference (runtime/reference/reference.h),
// which shares none of its sampling code.
#include "runtime/reference/path_reference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/transport/ray_caster.h"
#include "runtime/env/env_map.h"
#include "runtime/reference/reference.h"
#include "tests/testing/bowl_scene.h"

namespace wavebake {
namespace {

struct BowlSetup {
  Scene scene;
  SampleSet samples;
};

// Every 29th vertex of a 16×32 bowl as a sample (pole to rim), albedo a.
BowlSetup Bowl(float a) {
  BowlSetup b;
  b.scene.name = "bowl";
  b.scene.meshes = {test_support::BowlMesh(16, 32, a)};
  const Mesh& m = b.scene.meshes[0];
  for (size_t v = 0; v < m.positions.size(); v += 29) {
    b.samples.grid.push_back(static_cast<int32_t>(b.samples.position.size()));
    b.samples.position.push_back(m.positions[v]);
    b.samples.normal.push_back(m.normals[v]);
    b.samples.albedo.push_back(m.albedo);
  }
  b.samples.width = static_cast<int>(b.samples.position.size());
  b.samples.height = 1;
  return b;
}

TEST(PathReference, SphericalCavityMatchesTheGeometricSeries) {
  const float a = 0.8f;
  const BowlSetup bowl = Bowl(a);
  absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:constant");
  ASSERT_TRUE(env.ok());
  for (int bounces : {0, 1, 2, 8}) {
    absl::StatusOr<ReferenceResult> r = ComputePathReference(
        bowl.scene, bowl.samples, *env, {.bounces = bounces, .target_rel_se = 0.004});
    ASSERT_TRUE(r.ok()) << r.status();
    EXPECT_TRUE(r->converged);
    // B(x) = ρ(x) Σ T_b·1, the same for every point of the cavity.
    const double expected = a * test_support::BowlSeries(a, bounces);
    double mean = 0;
    for (int s = 0; s < bowl.samples.size(); ++s) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(r->rgb[3 * s + c], expected, 0.03 * expected) << "sample " << s;
        mean += r->rgb[3 * s + c];
      }
    }
    mean /= 3.0 * bowl.samples.size();
    EXPECT_NEAR(mean, expected, 0.01 * expected) << bounces << " bounces";
  }
}

// No bounce: the path tracer's first vertex is the direct reference's
// estimator of the same integral; the two agree within their errors.
TEST(PathReference, NoBounceAgreesWithTheDirectReference) {
  const BowlSetup bowl = Bowl(0.5f);
  absl::StatusOr<RayCaster> caster = RayCaster::Build(bowl.scene);
  ASSERT_TRUE(caster.ok());
  absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:sky");
  ASSERT_TRUE(env.ok());
  absl::StatusOr<ReferenceResult> path =
      ComputePathReference(bowl.scene, bowl.samples, *env, {.bounces = 0, .target_rel_se = 0.003});
  ReferenceOptions direct_options;
  direct_options.target_rel_se = 0.003;
  absl::StatusOr<ReferenceResult> direct =
      ComputeReference(*caster, bowl.samples, *env, direct_options);
  ASSERT_TRUE(path.ok() && direct.ok());
  for (size_t i = 0; i < path->rgb.size(); ++i) {
    const double se = std::hypot(path->standard_error[i], direct->standard_error[i]);
    EXPECT_NEAR(path->rgb[i], direct->rgb[i], 5 * se + 1e-6) << "value " << i;
  }
}

// Bit-identical for any number of threads: one stream per sample.
TEST(PathReference, SameOnAnyNumberOfThreads) {
  const BowlSetup bowl = Bowl(0.6f);
  absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:sky");
  ASSERT_TRUE(env.ok());
  const PathReferenceOptions one{.bounces = 2, .target_rel_se = 0.02, .threads = 1};
  PathReferenceOptions three = one;
  three.threads = 3;
  absl::StatusOr<ReferenceResult> a = ComputePathReference(bowl.scene, bowl.samples, *env, one);
  absl::StatusOr<ReferenceResult> b = ComputePathReference(bowl.scene, bowl.samples, *env, three);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->rgb, b->rgb);
  EXPECT_EQ(a->rays, b->rays);
}

}  // namespace
}  // namespace wavebake
