#include "core/transport/ray_caster.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tests/core/test_shapes.h"

namespace wavebake {
namespace {

using test_shapes::BuildOrDie;
using test_shapes::Quad;
using test_shapes::SceneOf;
using test_shapes::Triangle;
using ::testing::HasSubstr;

constexpr float kInf = std::numeric_limits<float>::infinity();

void ExpectNear(Vec3 a, Vec3 b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

Scene UnitTriangle() { return SceneOf({Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0})}); }

TEST(RayCasterTest, UnitTriangleOccludesRaysThroughIt) {
  const RayCaster caster = BuildOrDie(UnitTriangle());
  const Vec3 down{0, 0, -1}, up{0, 0, 1};
  EXPECT_TRUE(caster.Occluded({0.25f, 0.25f, 1}, down, 0, 2));
  EXPECT_TRUE(caster.Occluded({0.25f, 0.25f, -1}, up, 0, kInf));    // back face counts too
  EXPECT_FALSE(caster.Occluded({0.25f, 0.25f, 1}, down, 0, 0.5f));  // stops short (t = 1)
  EXPECT_FALSE(caster.Occluded({0.25f, 0.25f, 1}, down, 1.5f, 3));  // starts past it
  EXPECT_FALSE(caster.Occluded({0.25f, 0.25f, 1}, up, 0, kInf));    // points away
  EXPECT_FALSE(caster.Occluded({0.75f, 0.75f, 1}, down, 0, kInf));  // beyond the hypotenuse
  EXPECT_FALSE(caster.Occluded({-0.1f, 0.5f, 1}, down, 0, kInf));   // left of the x = 0 edge
  // Unnormalized direction: t counts in units of |dir|, the plane is at t = 0.5.
  EXPECT_TRUE(caster.Occluded({0.25f, 0.25f, 1}, {0, 0, -2}, 0, 0.6f));
  EXPECT_FALSE(caster.Occluded({0.25f, 0.25f, 1}, {0, 0, -2}, 0, 0.4f));
}

// Every fan kernel agrees with the analytic ray–triangle answer.
TEST(RayCasterTest, OccludedFanMatchesAnalyticTriangle) {
  const RayCaster caster = BuildOrDie(UnitTriangle());
  const Vec3 o{0.3f, 0.3f, 1};
  std::mt19937 rng(7);
  std::normal_distribution<float> gauss;
  std::vector<float> x, y, z;
  std::vector<uint8_t> expected;
  while (x.size() < 101) {  // not a multiple of 8 or 16: exercises the tail packet
    const Vec3 d = Normalize({gauss(rng), gauss(rng), gauss(rng)});
    bool hit = false;
    if (d.z < 0) {
      const Vec3 p = o + d * (-o.z / d.z);
      const float margin = std::min({p.x, p.y, 1 - p.x - p.y});
      if (std::fabs(margin) < 1e-3f) continue;  // too close to an edge to call
      hit = margin > 0;
    }
    x.push_back(d.x), y.push_back(d.y), z.push_back(d.z);
    expected.push_back(hit);
  }
  ASSERT_GT(std::count(expected.begin(), expected.end(), 1), 5);
  for (FanKernel kernel :
       {FanKernel::kSingle, FanKernel::kPacket8, FanKernel::kPacket16, FanKernel::kStream}) {
    std::vector<uint8_t> occluded(x.size(), 7);
    caster.OccludedFan(o, {x, y, z}, 0, kInf, occluded, kernel);
    EXPECT_EQ(occluded, expected) << "kernel " << static_cast<int>(kernel);
  }
}

TEST(RayCasterTest, FirstHitMatchesRayPlaneIntersection) {
  const Vec3 c{0.5f, -0.2f, 0.3f};
  const Vec3 n = Normalize({0.3f, 0.2f, 1});
  const RayCaster caster = BuildOrDie(SceneOf({Quad(c, n, 10)}));
  const Vec3 origins[] = {{0, 0, 3}, {1, 2, 4}, {-2, 1, -3}};
  const Vec3 targets[] = {{0.1f, 0.2f, 0}, {-1, 0.5f, 0}, {2, -2, 0}};
  for (Vec3 o : origins) {
    for (Vec3 target : targets) {
      const Vec3 d = Normalize(target - o);
      const float t = Dot(c - o, n) / Dot(d, n);  // analytic ray–plane distance
      const std::optional<Hit> hit = caster.FirstHit(o, d);
      ASSERT_TRUE(hit.has_value());
      EXPECT_NEAR(hit->t, t, 1e-5f * t);
      ExpectNear(hit->position, o + d * t, 1e-4f);
      ExpectNear(hit->normal, n, 1e-5f);  // geometric normal: the quad is CCW about n
      EXPECT_EQ(hit->mesh, 0u);
      EXPECT_LT(hit->triangle, 2u);
    }
  }
  EXPECT_FALSE(caster.FirstHit({0, 0, 3}, {0, 0, 1}).has_value());         // points away
  EXPECT_FALSE(caster.FirstHit({0, 0, 3}, {0, 0, -1}, 0, 1).has_value());  // tfar short
}

TEST(RayCasterTest, FirstHitInterpolatesVertexNormals) {
  Mesh m = Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  m.normals = {Normalize({-1, 0, 1}), Normalize({1, 0, 1}), {0, 0, 1}};
  const RayCaster caster = BuildOrDie(SceneOf({m}));
  const float u = 0.2f, v = 0.5f;  // barycentrics of the hit point
  const std::optional<Hit> hit = caster.FirstHit({u, v, 2}, {0, 0, -1});
  ASSERT_TRUE(hit.has_value());
  const Vec3 expected = Normalize(m.normals[0] * (1 - u - v) + m.normals[1] * u + m.normals[2] * v);
  ExpectNear(hit->normal, expected, 1e-5f);
  EXPECT_NEAR(hit->t, 2, 1e-6f);
}

// Vertex ids are global across meshes in scene order; the nearest vertex is
// the closest corner in space.
TEST(RayCasterTest, FirstHitReportsNearestGlobalVertex) {
  const Scene scene = SceneOf({Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "a"),
                               Triangle({0, 0, -1}, {4, 0, -1}, {0, 4, -1}, "b")});
  const RayCaster caster = BuildOrDie(scene);
  EXPECT_EQ(caster.vertex_count(), 6u);
  // Misses "a" (beyond its hypotenuse) and lands on "b" near its vertex 1 (4, 0).
  std::optional<Hit> hit = caster.FirstHit({3.5f, 0.2f, 2}, {0, 0, -1});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->mesh, 1u);
  EXPECT_EQ(hit->triangle, 0u);
  EXPECT_EQ(hit->vertex, 3u + 1u);
  hit = caster.FirstHit({0.1f, 0.8f, 2}, {0, 0, -1});  // lands on "a" near (0, 1)
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->mesh, 0u);
  EXPECT_EQ(hit->vertex, 2u);
}

TEST(RayCasterTest, BoundsDiagonalAndEpsilonScaleWithTheScene) {
  const Scene scene = SceneOf(
      {Triangle({-1, 0, 0}, {2, 0, 0}, {0, 4, 0}), Triangle({0, 0, 12}, {1, 0, 12}, {0, 1, 12})});
  const RayCaster caster = BuildOrDie(scene);
  ExpectNear(caster.bounds().lower, {-1, 0, 0}, 0);
  ExpectNear(caster.bounds().upper, {2, 4, 12}, 0);
  EXPECT_FLOAT_EQ(caster.Diagonal(), 13);  // sqrt(3² + 4² + 12²)
  EXPECT_FLOAT_EQ(caster.DefaultEpsilon(), 13e-4f);
}

TEST(RayCasterTest, MovedCasterStillAnswers) {
  RayCaster a = BuildOrDie(UnitTriangle());
  RayCaster b = std::move(a);
  EXPECT_TRUE(b.Occluded({0.25f, 0.25f, 1}, {0, 0, -1}, 0, kInf));
  RayCaster c = BuildOrDie(SceneOf({Quad({0, 0, 5}, {0, 0, 1}, 1)}));
  c = std::move(b);
  EXPECT_TRUE(c.Occluded({0.25f, 0.25f, 1}, {0, 0, -1}, 0, kInf));
  EXPECT_FALSE(c.Occluded({0.25f, 0.25f, 1}, {0, 0, 1}, 0, kInf));
}

TEST(RayCasterTest, BuildRejectsBadScenesNamingTheInput) {
  auto error_of = [](const Scene& s) { return RayCaster::Build(s).status(); };
  Scene empty;
  empty.name = "void";
  EXPECT_THAT(error_of(empty).message(), HasSubstr("scene 'void' has no meshes"));

  Mesh no_triangles = Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "flat");
  no_triangles.triangles.clear();
  EXPECT_THAT(error_of(SceneOf({no_triangles})).message(), HasSubstr("mesh 0 ('flat') is empty"));

  Mesh nan = Triangle({0, 0, 0}, {std::nanf(""), 0, 0}, {0, 1, 0}, "bad");
  const absl::Status s = error_of(SceneOf({Quad({0, 0, 0}, {0, 0, 1}, 1), nan}));
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("mesh 1 ('bad') vertex 1 is not finite"));

  Mesh out_of_range = Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "idx");
  out_of_range.triangles.push_back({0, 1, 9});
  EXPECT_THAT(error_of(SceneOf({out_of_range})).message(),
              HasSubstr("mesh 0 ('idx') triangle 1 references vertex 9 of 3"));

  Mesh normals = Triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "nrm");
  normals.normals = {{0, 0, 1}};
  EXPECT_THAT(error_of(SceneOf({normals})).message(),
              HasSubstr("mesh 0 ('nrm') has 1 normals for 3 vertices"));
}

}  // namespace
}  // namespace wavebake
