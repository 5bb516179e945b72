#include "core/transport/bounce_gather.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/transport/transport_row.h"
#include "tests/core/test_shapes.h"
#include "tests/testing/bowl_scene.h"

namespace wavebake {
namespace {

using test_shapes::BuildOrDie;
using test_shapes::Quad;
using test_shapes::SceneOf;

Mesh Bowl(int rings, int segments, Vec3 albedo) {
  Mesh m = test_support::BowlMesh(rings, segments, 1.0f);
  m.albedo = albedo;
  return m;
}

// Every vertex a sample, cell c = vertex c (the tail of the grid masked).
SampleSet VertexSamples(const Scene& scene, int width, int height) {
  SampleSet s;
  s.width = width;
  s.height = height;
  for (const Mesh& m : scene.meshes) {
    s.position.insert(s.position.end(), m.positions.begin(), m.positions.end());
    s.normal.insert(s.normal.end(), m.normals.begin(), m.normals.end());
    s.albedo.insert(s.albedo.end(), m.positions.size(), m.albedo);
  }
  s.grid.assign(size_t(width) * height, -1);
  for (int v = 0; v < s.size(); ++v) {
    s.grid[v] = v;
    s.vertex.push_back(v);
  }
  return s;
}

// T_0·1 per cell (L ≡ 1: the row's sum), traced by the direct bake's row.
std::vector<float> DirectUnderUniformLight(const RayCaster& caster, const SampleSet& s, int n,
                                           int k) {
  const Cubemap cubemap(n);
  absl::StatusOr<JitterPattern> pattern = MakeJitterPattern(cubemap, k, 7);
  EXPECT_TRUE(pattern.ok());
  std::vector<float> out(s.cells(), 0.0f), row(cubemap.size());
  for (int c = 0; c < s.cells(); ++c) {
    if (s.grid[c] < 0) continue;
    TransportRow(caster, cubemap, *pattern, s.position[s.grid[c]], s.normal[s.grid[c]],
                 caster.DefaultEpsilon(), row, nullptr);
    out[c] = static_cast<float>(std::accumulate(row.begin(), row.end(), 0.0));
  }
  return out;
}

// The spherical cavity (tests/testing/bowl_scene.h): under L ≡ 1 every
// point of the bowl has Σ_{b≤B} T_b·1 = f Σ_{b≤B} (a(1−f))^b, f = 1/2. With
// a = 0.8 the bounces add 40 %, 16 %, 6.4 % of the direct light.
TEST(BounceGatherTest, SphericalCavityMatchesTheGeometricSeries) {
  const float a = 0.8f;
  const Scene scene = SceneOf({test_support::BowlMesh(24, 48, a)});
  const RayCaster caster = BuildOrDie(scene);
  const SampleSet s = VertexSamples(scene, 64, 32);
  ASSERT_LE(s.size(), s.cells());

  const std::vector<float> direct = DirectUnderUniformLight(caster, s, 16, 4);
  absl::StatusOr<BounceGather> g = MakeBounceGather(scene, caster, s, {.rays = 256, .seed = 3});
  ASSERT_TRUE(g.ok()) << g.status();
  EXPECT_EQ(g->rays, 256);

  std::vector<float> previous = direct, next(s.cells()), total = direct;
  for (int b = 1; b <= 3; ++b) {
    g->Apply(previous, next);
    const double expected = test_support::BowlSeries(a, b);
    for (int c = 0; c < s.cells(); ++c) total[c] += next[c];
    previous = next;

    double mean = 0;
    for (int c = 0; c < s.size(); ++c) mean += total[c];
    mean /= s.size();
    EXPECT_NEAR(mean, expected, 0.01 * expected) << "bounces " << b;
    // Uniform by the form-factor property: each vertex, not just the mean
    // (the gather's own noise, R = 256 stratified rays, is well below 3 %).
    for (int c = 0; c < s.size(); ++c)
      ASSERT_NEAR(total[c], expected, 0.03 * expected) << "bounces " << b << " vertex " << c;
  }
  // The direct light alone is the cavity's f (the setting, not the gather).
  const double direct_mean =
      std::accumulate(direct.begin(), direct.begin() + s.size(), 0.0) / s.size();
  EXPECT_NEAR(direct_mean, test_support::kBowlOpening, 0.01 * test_support::kBowlOpening);
}

// A plane alone: every ray escapes, nothing bounces.
TEST(BounceGatherTest, OpenPlaneHasNoBounce) {
  Mesh plane = Quad({0, 0, 0}, {0, 0, 1}, 1);
  plane.normals.assign(plane.positions.size(), Vec3{0, 0, 1});
  const Scene scene = SceneOf({plane});
  const RayCaster caster = BuildOrDie(scene);
  absl::StatusOr<BounceGather> g =
      MakeBounceGather(scene, caster, VertexSamples(scene, 2, 2), {.rays = 16});
  ASSERT_TRUE(g.ok()) << g.status();
  EXPECT_EQ(g->entries(), 0);
  EXPECT_EQ(g->hits, 0u);
}

// The blocked product (TRANSFORM_COLUMNS applies G to kMaxBlock columns at once)
// gives every vector the bits of the one-vector product, also where it skips
// the sources that are zero in every vector of the block (+0 and −0 alike;
// values of both signs, so sums can cancel).
TEST(BounceGatherTest, BlockedProductIsTheProductOfEachVector) {
  const Scene scene = SceneOf({Bowl(6, 12, {0.5f, 0.7f, 0.9f})});
  const RayCaster caster = BuildOrDie(scene);
  const SampleSet s = VertexSamples(scene, 16, 8);
  absl::StatusOr<BounceGather> g = MakeBounceGather(scene, caster, s, {.rays = 16});
  ASSERT_TRUE(g.ok()) << g.status();
  for (int n : {1, 5, BounceGather::kMaxBlock}) {
    std::vector<float> block(size_t(s.cells()) * n), out(block.size());
    for (size_t i = 0; i < block.size(); ++i) {
      const size_t cell = i / n;
      block[i] = cell % 3 == 0 ? (cell % 2 ? -0.0f : 0.0f)
                 : cell % 3 == 1 && i % n != 0 ? 0.0f
                                               : std::sin(0.37f * i);
    }
    g->ApplyBlock(block, out, n);
    std::vector<float> one(s.cells()), expected(s.cells());
    for (int k = 0; k < n; ++k) {
      for (int c = 0; c < s.cells(); ++c) one[c] = block[size_t(c) * n + k];
      g->Apply(one, expected);
      for (int c = 0; c < s.cells(); ++c)
        ASSERT_EQ(out[size_t(c) * n + k], expected[c]) << "n " << n << " vector " << k;
    }
  }
}

// The operator depends on (scene, samples, seed, rays) only: not on threads.
TEST(BounceGatherTest, SameOperatorOnAnyNumberOfThreads) {
  const Scene scene = SceneOf({Bowl(6, 12, {0.5f, 0.7f, 0.9f})});
  const RayCaster caster = BuildOrDie(scene);
  const SampleSet s = VertexSamples(scene, 16, 8);
  absl::StatusOr<BounceGather> one = MakeBounceGather(scene, caster, s, {.rays = 20, .threads = 1});
  absl::StatusOr<BounceGather> three =
      MakeBounceGather(scene, caster, s, {.rays = 20, .threads = 3});
  ASSERT_TRUE(one.ok() && three.ok());
  EXPECT_EQ(one->rays, 25);  // rounded up to a square
  EXPECT_EQ(one->offsets, three->offsets);
  EXPECT_EQ(one->source, three->source);
  EXPECT_EQ(one->weight, three->weight);
  // Every weight is ρ̄ β / R with ρ̄ = 0.7: a row sums to ≤ ρ̄.
  for (int c = 0; c < s.size(); ++c) {
    double sum = 0;
    for (int64_t e = one->offsets[c]; e < one->offsets[c + 1]; ++e) sum += one->weight[e];
    EXPECT_LE(sum, 0.7 + 1e-5);
    EXPECT_GT(sum, 0.0);  // inside a bowl, some ray always hits
  }
  // A different seed is a different (equally valid) operator.
  absl::StatusOr<BounceGather> other = MakeBounceGather(scene, caster, s, {.rays = 20, .seed = 2});
  ASSERT_TRUE(other.ok());
  EXPECT_NE(one->weight, other->weight);
}

// `auto` on the cavity: G·1 = a(1 − f)·1 exactly (every ray that stays in
// the bowl finds albedo a), so the estimates are 0.4^b for a = 0.8, and a 1 %
// target (half of it, 0.005, for the bounces left out) needs B = 5: 0.4⁶ =
// 0.0041 ≤ 0.005 < 0.4⁵ = 0.0102.
TEST(BounceGatherTest, AutoStopsWhenTheNextBounceFitsHalfTheBudget) {
  const Scene scene = SceneOf({test_support::BowlMesh(12, 24, 0.8f)});
  const RayCaster caster = BuildOrDie(scene);
  const SampleSet s = VertexSamples(scene, 32, 16);
  absl::StatusOr<BounceGather> g = MakeBounceGather(scene, caster, s, {.rays = 256});
  ASSERT_TRUE(g.ok());
  const AutoBounceChoice choice = AutoBounces(*g, s.grid, 0.01, 8);
  EXPECT_EQ(choice.bounces, 5);
  ASSERT_EQ(choice.estimate.size(), 7u);
  // The rate per bounce (the tessellated bowl and its rim lose a little).
  for (int b = 1; b < 7; ++b)
    EXPECT_NEAR(std::pow(choice.estimate[b], 1.0 / b), 0.4, 0.03 * 0.4) << b;
  EXPECT_EQ(AutoBounces(*g, s.grid, 0.5, 8).bounces, 1);  // 0.4 > 0.25, 0.16 ≤ 0.25
  EXPECT_EQ(AutoBounces(*g, s.grid, 0.0, 3).bounces, 3);  // no budget: the most allowed
}

TEST(BounceGatherTest, RefusesSamplesThatAreNotVertices) {
  const Scene scene = SceneOf({Bowl(4, 8, {1, 1, 1})});
  const RayCaster caster = BuildOrDie(scene);
  SampleSet s = VertexSamples(scene, 8, 8);
  s.vertex.clear();  // a camera layout's samples
  absl::StatusOr<BounceGather> g = MakeBounceGather(scene, caster, s, {});
  EXPECT_EQ(g.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(g.status().message().find("bounces"), std::string::npos);
}

}  // namespace
}  // namespace wavebake
