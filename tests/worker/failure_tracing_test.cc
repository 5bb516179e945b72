// Where tracing fails (issue 7, docs/RESULTS.md "Where methods fail"):
//   * the ray offset ε (DESIGN.md §1: rays start at x + ε n). Too large, the
//     origin jumps past a thin occluder and light leaks through it: under the
//     disk of disk-over-plane the row sum, analytically 1 − r²/(r²+h²), goes
//     to the unoccluded 1 once ε > h. Too small, a sample on a curved mesh
//     sees its own triangles: at the top of the tessellated sphere, whose
//     upper hemisphere is open (row sum 1, the white furnace), ε → 0 lets the
//     rays start on the surface itself.
//   * degenerate triangles: dropped and counted by the scene gate, and the
//     rest of the mesh bakes correctly (the white furnace on an open plane).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numeric>
#include <vector>

#include "core/builtin_scenes.h"
#include "tests/worker/column_test_support.h"
#include "worker/bake_context.h"
#include "worker/transport_row.h"

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

TEST(FailureTracingTest, EpsilonPastAThinOccluderLeaksLight) {
  auto ctx = MakeBakeContext("builtin:disk-over-plane", RowJob("grid"));
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  const double r2 = builtin::kDiskRadius * builtin::kDiskRadius;
  const double h2 = builtin::kDiskHeight * builtin::kDiskHeight;
  const double shadowed = 1 - r2 / (r2 + h2);  // ≈ 0.69
  const Vec3 centre = builtin::kDiskPlaneCentre, up{0, 1, 0};

  EXPECT_NEAR(RowSum(**ctx, centre, up, (*ctx)->epsilon), shadowed, 0.01);
  // Still below the disk: the same answer.
  EXPECT_NEAR(RowSum(**ctx, centre, up, 0.5f * builtin::kDiskHeight), shadowed, 0.01);
  // Past it: the disk is behind the ray origins and the sample sees the sky.
  EXPECT_NEAR(RowSum(**ctx, centre, up, 1.2f * builtin::kDiskHeight), 1.0, 0.005);
}

// The sphere's top vertex (its pole) and normal.
Vec3 SphereTop() { return builtin::kSphereCentre + Vec3{0, builtin::kSphereRadius, 0}; }

TEST(FailureTracingTest, EpsilonTooSmallOnACurvedMeshSelfShadows) {
  auto ctx = MakeBakeContext("builtin:sphere-plane", RowJob("grid"));
  ASSERT_TRUE(ctx.ok()) << ctx.status();
  const Vec3 up{0, 1, 0};
  // The default ε (1e-4 of the scene diagonal): the open hemisphere's 1.
  TransportStats good;
  EXPECT_NEAR(RowSum(**ctx, SphereTop(), up, (*ctx)->epsilon, &good), 1.0, 0.005);
  EXPECT_EQ(good.rays_occluded, 0u);

  // Points just off the pole on the true sphere (between vertices, where the
  // tessellation lies below them) with ε = 0: unaffected, the polyhedron is
  // inscribed. Points slightly inside the surface — what float rounding of a
  // position does — with a tiny ε see their own triangles: acne.
  const Vec3 inside = SphereTop() - up * 1e-4f;
  TransportStats acne;
  const double sum = RowSum(**ctx, inside, up, 1e-9f, &acne);
  EXPECT_GT(acne.rays_occluded, 0u);
  EXPECT_LT(sum, 0.5) << "self-shadowed: the sample is under its own surface";
  // The default ε lifts the same point out again.
  EXPECT_NEAR(RowSum(**ctx, inside, up, (*ctx)->epsilon), 1.0, 0.005);
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
      obj << "f " << a << " " << c << " " << b << "\n" << "f " << b << " " << c << " " << d << "\n";
    }
  }
  obj << "f 1 1 2\n"     // repeated index
      << "f 1 17 6\n"    // coincident positions: zero area
      << "f 1 2 3\n";    // collinear: zero area
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
