// Where tracing fails (docs/RESULTS.md "Where methods fail"):
//   * the ray offset ε (DESIGN.md §1: rays start at x + ε n). Too large, the
//     origin jumps past a thin occluder and light leaks through it: under the
//     disk of disk-over-plane the row sum, analytically 1 − r²/(r²+h²), goes
//     to the unoccluded 1 once ε > h (and is biased dark before that: the
//     sample answers for a point ε higher). Too small, a sample on a curved
//     mesh sees its own triangles: on the cap of the tessellated sphere,
//     whose hemisphere is open (row sum ≈ 1, the white furnace), ε below the
//     float spacing of the positions starts the rays on the surface itself.
//   * degenerate triangles: dropped and counted by the scene gate, and the
//     rest of the mesh bakes correctly (the white furnace on an open plane).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numeric>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "core/transport/transport_row.h"
#include "tests/worker/column_test_support.h"
#include "worker/tiles/bake_context.h"

namespace wavebake {
namespace {

using column_testing::ScratchDir;

BakeParams RowJob(const std::string& layout) {
  BakeParams p;
  p.light_res = 16;
  p.supersample = 4;
  p.layout = layout;
  return p;
}

// Σ_m T[s,m] at (position, normal) with offset epsilon: with L ≡ 1 this is
// the sample's irradiance fraction, 1 when nothing occludes.
double RowSum(const BakeContext& ctx, Vec3 position, Vec3 normal, float epsilon,
              TransportStats* stats = nullptr) {
  std::vector<float> row(ctx.cubemap.size());
  TransportRow(ctx.caster, ctx.cubemap, ctx.jitter, position, normal, epsilon, row, stats);
  return std::accumulate(row.begin(), row.end(), 0.0);
}

// Σ_m T at height y under the disk's centre: it blocks the cosine-weighted
// fraction r²/(r² + (h − y)²) of the upper hemisphere (core/scene/builtin_scenes.h).
double UnderDisk(double y) {
  const double r2 = builtin::kDiskRadius * builtin::kDiskRadius;
  const double gap = builtin::kDiskHeight - y;
  return 1 - r2 / (r2 + gap * gap);
}

TEST(FailureTracingTest, EpsilonPastAThinOccluderLeaksLight) {
  auto ctx = MakeBakeContext("builtin:disk-over-plane", RowJob("grid"));
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  const Vec3 centre = builtin::kDiskPlaneCentre, up{0, 1, 0};
  const float h = builtin::kDiskHeight;

  // The default ε: the ground point's own answer (≈ 0.69).
  EXPECT_NEAR(RowSum(**ctx, centre, up, (*ctx)->epsilon), UnderDisk(0), 0.01);
  // A large ε moves the rays' origin up: the sample answers for a point
  // ε higher, where the disk looks bigger (0.36 at ε = h/2) — biased dark.
  EXPECT_NEAR(RowSum(**ctx, centre, up, 0.5f * h), UnderDisk(0.5 * h), 0.01);
  // Past the disk its occlusion is gone: the sample sees the open sky.
  EXPECT_NEAR(RowSum(**ctx, centre, up, 1.2f * h), 1.0, 0.005);
}

// Measured on the sphere's cap (the 257 vertices with n_y ≥ 0.9, N = 16,
// K = 4): ε = 1e-9 or less — below the float spacing of the positions,
// ~6e-8 — loses 98 % of the light on average (775 100 rays hit the vertex's
// own triangles at t ≈ 0); from ε = 1e-7 up the sums equal the default ε's.
TEST(FailureTracingTest, EpsilonTooSmallOnACurvedMeshSelfShadows) {
  auto ctx = MakeBakeContext("builtin:sphere-plane", RowJob("grid"));
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  const Mesh& sphere = (*ctx)->scene.meshes.at(1);
  ASSERT_EQ(sphere.name, "sphere");
  double tiny_sum = 0, good_sum = 0;
  int cap = 0, poles = 0;
  for (size_t i = 0; i < sphere.positions.size(); ++i) {
    const Vec3 x = sphere.positions[i], n = sphere.normals[i];
    if (n.y < 0.9f) continue;
    ++cap;
    const double good = RowSum(**ctx, x, n, (*ctx)->epsilon);
    good_sum += good;
    tiny_sum += RowSum(**ctx, x, n, 1e-9f);
    // Above the sphere's top nothing occludes: the white furnace's 1.
    if (n.y == 1.0f) {
      ++poles;
      EXPECT_NEAR(good, 1.0, 0.005) << "pole";
    }
  }
  ASSERT_EQ(poles, 1);
  ASSERT_GT(cap, 100);
  EXPECT_GT(good_sum / cap, 0.99) << "the cap sees (almost) the whole open hemisphere";
  EXPECT_LT(tiny_sum / cap, 0.2 * good_sum / cap) << "acne: rays hit their own triangles";
}

// A 4×4-vertex plane (18 triangles) plus three degenerate ones: a repeated
// index, two coincident vertices, three collinear vertices.
void WritePlaneWithDegenerates(const std::filesystem::path& path) {
  std::ofstream obj(path);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) obj << "v " << i << " 0 " << j << "\n";
  obj << "v 0 0 0\n";  // 17: coincides with vertex 1
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const int a = 1 + j * 4 + i, b = a + 1, c = a + 4, d = c + 1;
      obj << "f " << a << " " << c << " " << b << "\n"
          << "f " << b << " " << c << " " << d << "\n";
    }
  }
  obj << "f 1 1 2\n"   // repeated index
      << "f 1 17 6\n"  // coincident positions: zero area
      << "f 1 2 3\n";  // collinear: zero area
}

TEST(FailureTracingTest, DegenerateTrianglesAreDroppedCountedAndHarmless) {
  ScratchDir dir;
  const auto path = dir.path() / "plane.obj";
  WritePlaneWithDegenerates(path);
  auto ctx = MakeBakeContext(path.string(), RowJob("hilbert:8x8"));
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  EXPECT_EQ((*ctx)->scene_report.dropped_triangles, 3);
  int triangles = 0;
  for (const Mesh& m : (*ctx)->scene.meshes) triangles += int(m.triangles.size());
  EXPECT_EQ(triangles, 18);
  // Nothing above an open plane: every sample's row sums to 1.
  const SampleSet& s = (*ctx)->samples;
  ASSERT_GE(s.size(), 16);
  for (int i = 0; i < s.size(); ++i)
    EXPECT_NEAR(RowSum(**ctx, s.position[i], s.normal[i], (*ctx)->epsilon), 1.0, 0.005) << i;
}

}  // namespace
}  // namespace wavebake
