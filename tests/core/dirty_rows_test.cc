// The dirty-row test of an update bake is conservative: against the rows
// traced in full in the old and the new scene (brute force and refinement,
// compared bit for bit), every row that differs was flagged; a small object
// moved from behind a wall into a sample's view is caught; and samples the
// edit cannot reach (inside a closed shed) are left clean.
#include "core/transport/dirty_rows.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/scene/builtin_shapes.h"
#include "core/scene/scene_check.h"
#include "core/scene/scene_diff.h"
#include "core/transport/refine_plan.h"
#include "core/transport/refined_row.h"
#include "core/transport/transport_row.h"
#include "tests/core/test_shapes.h"

namespace wavebake {
namespace {

using test_shapes::BuildOrDie;
using test_shapes::Quad;

constexpr float kEps = 1e-4f;

Mesh Box(std::string name, Vec3 lo, Vec3 hi) {
  Mesh m;
  m.name = std::move(name);
  AppendOpenBox(m, lo, hi, 2);
  return m;
}

// Ground, a wall at z = -1 facing +z, a closed shed over [1, 1.6]² and a
// 0.1-wide box at `box_at` (its foot).
Scene World(Vec3 box_at) {
  Scene s;
  s.name = "dirty-rows";
  s.meshes.push_back(Quad({0, 0, 0}, {0, 1, 0}, 2.5f, "ground"));
  s.meshes.push_back(Quad({0, 0.6f, -1}, {0, 0, 1}, 0.6f, "wall"));
  s.meshes.push_back(Box("shed", {1, 0, 1}, {1.6f, 0.3f, 1.6f}));
  s.meshes.push_back(Box("box", box_at - Vec3{0.05f, 0, 0.05f}, box_at + Vec3{0.05f, 0.1f, 0.05f}));
  EXPECT_TRUE(CheckAndRepairScene(s, nullptr).ok());
  return s;
}

struct Sample {
  Vec3 position, normal;
};

// Ground points every 0.2 over [-2, 2]², 1 mm above the quad, and three in
// the shed.
std::vector<Sample> Samples() {
  std::vector<Sample> s;
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j) s.push_back({{0.2f * i, 1e-3f, 0.2f * j}, {0, 1, 0}});
  for (float x : {1.15f, 1.3f, 1.45f}) s.push_back({{x, 1e-3f, 1.3f}, {0, 1, 0}});
  return s;
}

class DirtyRowsTest : public ::testing::Test {
 protected:
  const Cubemap cubemap{16};
  const JitterPattern pattern = *MakeJitterPattern(cubemap, 4, 7);
  const RefinePlan plan{cubemap, pattern, RefineOptions{}};
  // The box moves from behind the wall (z = -1.5) to the open ground.
  const Scene old_scene = World({0, 0, -1.5f}), new_scene = World({0.5f, 0, 0.5f});
  const SceneDiff diff = DiffScenes(old_scene, new_scene);

  DirtyRowTest Test(DirtyRowOptions options = {}) const {
    absl::StatusOr<DirtyRowTest> t =
        DirtyRowTest::Build(ChangedGeometry(old_scene, new_scene, diff),
                            UnchangedGeometry(new_scene, diff), pattern, options);
    EXPECT_TRUE(t.ok()) << t.status();
    return *std::move(t);
  }
  // Whether the sample's row (brute force or refined) differs in any bit.
  bool RowDiffers(const RayCaster& a, const RayCaster& b, const Sample& s) const {
    std::vector<float> ra(cubemap.size()), rb(cubemap.size());
    TransportRow(a, cubemap, pattern, s.position, s.normal, kEps, ra, nullptr);
    TransportRow(b, cubemap, pattern, s.position, s.normal, kEps, rb, nullptr);
    if (ra != rb) return true;
    RefineScratch scratch;
    RefinedTransportRow(a, cubemap, pattern, plan, s.position, s.normal, kEps, ra, nullptr,
                        scratch);
    RefinedTransportRow(b, cubemap, pattern, plan, s.position, s.normal, kEps, rb, nullptr,
                        scratch);
    return ra != rb;
  }
};

TEST_F(DirtyRowsTest, DiffSeesOnlyTheBox) {
  ASSERT_EQ(diff.removed, std::vector<int>{3});
  ASSERT_EQ(diff.added, std::vector<int>{3});
}

TEST_F(DirtyRowsTest, EveryRowThatChangesIsFlagged) {
  const RayCaster old_caster = BuildOrDie(old_scene), new_caster = BuildOrDie(new_scene);
  const DirtyRowTest test = Test();
  int changed = 0, flagged = 0;
  for (const Sample& s : Samples()) {
    const bool differs = RowDiffers(old_caster, new_caster, s);
    const bool may = test.MayChange(s.position, s.normal, kEps, nullptr);
    EXPECT_TRUE(may || !differs) << "row changed but not flagged at " << s.position.x << ", "
                                 << s.position.z;
    changed += differs;
    flagged += may;
  }
  // Not vacuous: the edit changes many rows, and the test leaves some clean.
  EXPECT_GT(changed, 50);
  EXPECT_LT(flagged, static_cast<int>(Samples().size()));
}

TEST_F(DirtyRowsTest, ObjectMovedIntoViewFromBehindTheWallIsCaught) {
  // (0.2, -0.8) is in front of the wall: the old box behind it was hidden
  // (its row then equals the box-less scene's), the new one is in the open.
  const Sample s{{0.2f, 1e-3f, -0.8f}, {0, 1, 0}};
  Scene without = old_scene;
  without.meshes.pop_back();
  ASSERT_FALSE(RowDiffers(BuildOrDie(old_scene), BuildOrDie(without), s));
  ASSERT_TRUE(RowDiffers(BuildOrDie(old_scene), BuildOrDie(new_scene), s));
  EXPECT_TRUE(Test().MayChange(s.position, s.normal, kEps, nullptr));
}

TEST_F(DirtyRowsTest, StaticOccludersKeepTheShedClean) {
  const DirtyRowTest filtered = Test(), coarse = Test({.static_occlusion = false});
  const Sample inside{{1.3f, 1e-3f, 1.3f}, {0, 1, 0}};
  DirtyRowStats stats;
  EXPECT_FALSE(filtered.MayChange(inside.position, inside.normal, kEps, &stats));
  EXPECT_GT(stats.rays_static, 0u);  // the box is in its cones: the shed blocked it
  // Without the occlusion test the bound alone flags it (still conservative).
  EXPECT_TRUE(coarse.MayChange(inside.position, inside.normal, kEps, nullptr));
}

// The patch of --update: old row + RowDelta is the new scene's brute-force
// row, against two full traces (TransportRow shares no code with RowDelta).
TEST_F(DirtyRowsTest, RowDeltaIsTheBruteForceRowsDifference) {
  DirtyRowTest test = Test();
  ASSERT_TRUE(
      test.SetPlacements(RemovedGeometry(old_scene, diff), AddedGeometry(new_scene, diff)).ok());
  const RayCaster old_caster = BuildOrDie(old_scene), new_caster = BuildOrDie(new_scene);
  std::vector<float> a(cubemap.size()), b(cubemap.size()), delta(cubemap.size());
  int patched = 0;
  for (const Sample& s : Samples()) {
    TransportRow(old_caster, cubemap, pattern, s.position, s.normal, kEps, a, nullptr);
    TransportRow(new_caster, cubemap, pattern, s.position, s.normal, kEps, b, nullptr);
    patched += test.RowDelta(s.position, s.normal, kEps, delta, nullptr);
    for (int m = 0; m < cubemap.size(); ++m)
      ASSERT_NEAR(a[m] + delta[m], b[m], 1e-6f)
          << "texel " << m << " of " << s.position.x << ", " << s.position.z;
  }
  EXPECT_GT(patched, 50);
}

TEST_F(DirtyRowsTest, ConesTraceFewRays) {
  const DirtyRowTest test = Test();
  DirtyRowStats stats;
  const Sample far_corner{{2, 1e-3f, 2}, {0, 1, 0}};
  (void)test.MayChange(far_corner.position, far_corner.normal, kEps, &stats);
  // Two 0.1-wide boxes seen from ≥ 1.8 away cover a few texels of 6·16².
  EXPECT_LT(stats.texels_in_cones, 100u);
  EXPECT_GT(stats.texels_in_cones, 0u);
}

}  // namespace
}  // namespace wavebake
