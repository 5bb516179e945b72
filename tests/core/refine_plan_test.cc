// The quadtree geometry of visibility refinement (core/transport/refine_plan.h).
#include "core/transport/refine_plan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace wavebake {
namespace {

struct Fixture {
  Cubemap cubemap;
  JitterPattern pattern;
  Fixture(int n) : cubemap(n), pattern(*MakeJitterPattern(cubemap, 4, 1)) {}
};

// Neighbours are the texels around: their centres are within two texel
// widths (√2 on the diagonal, a little more beyond a cube corner) — across
// face edges too, where a wrong face orientation would put them far apart.
TEST(RefinePlanTest, NeighboursAreAdjacentAcrossFaceEdges) {
  for (int n : {8, 16}) {
    const Fixture f(n);
    const RefinePlan plan(f.cubemap, f.pattern, {});
    const double texel = (std::numbers::pi / 2) / n;  // angle of a texel at a face centre
    int across = 0;
    for (int m = 0; m < f.cubemap.size(); ++m) {
      const Vec3 c = f.cubemap.TexelCenter(m);
      std::set<int32_t> seen;
      plan.AllNeighbourAnchors(0, m, [&](int32_t nb) {
        EXPECT_NE(nb, m);
        const double angle =
            std::acos(std::clamp(double(Dot(c, f.cubemap.TexelCenter(nb))), -1.0, 1.0));
        EXPECT_LT(angle, 2 * texel) << "N=" << n << " m=" << m << " neighbour " << nb;
        if (f.cubemap.TexelOf(nb).face != f.cubemap.TexelOf(m).face) ++across;
        seen.insert(nb);
        return true;
      });
      // 8 distinct neighbours, 7 at a cube corner (one diagonal is missing).
      EXPECT_GE(seen.size(), 7u) << m;
    }
    // Per face: 4(n−2) edge texels with 3 neighbours beyond the edge, 4
    // corners with 5.
    EXPECT_EQ(across, 6 * (4 * (n - 2) * 3 + 4 * 5)) << "N=" << n;
  }
}

// A block's probe texel lies inside it, is the probe of one of its
// children, and probes of neighbouring start blocks are staggered.
TEST(RefinePlanTest, AnchorsNestAndStagger) {
  const Fixture f(64);
  const RefinePlan plan(f.cubemap, f.pattern, {.start_spacing = 8});
  ASSERT_EQ(plan.start_level(), 3);
  std::set<std::pair<int, int>> offsets;
  for (int level = 1; level <= plan.start_level(); ++level) {
    const int per_edge = plan.BlocksPerEdge(level), size = 1 << level;
    for (int b = 0; b < plan.BlockCount(level); ++b) {
      const int face = b / (per_edge * per_edge), bx = b % per_edge, by = b / per_edge % per_edge;
      const Texel a = f.cubemap.TexelOf(plan.Anchor(level, b));
      EXPECT_EQ(a.face, face);
      EXPECT_GE(a.x, bx * size);
      EXPECT_LT(a.x, (bx + 1) * size);
      EXPECT_GE(a.y, by * size);
      EXPECT_LT(a.y, (by + 1) * size);
      const int child =
          (face * 2 * per_edge + 2 * by + (a.y - by * size) / (size / 2)) * 2 * per_edge + 2 * bx +
          (a.x - bx * size) / (size / 2);
      EXPECT_EQ(plan.Anchor(level - 1, child), plan.Anchor(level, b));
      if (level == plan.start_level()) offsets.insert({a.x - bx * size, a.y - by * size});
      // The probe is the anchor's ray 0.
      const Vec3 d = plan.ProbeDirection(level, b),
                 e = f.pattern.Direction(plan.Anchor(level, b), 0);
      EXPECT_EQ(d, e);
    }
  }
  EXPECT_GE(offsets.size(), 8u);  // not one lattice offset
  const RefinePlan regular(f.cubemap, f.pattern, {.start_spacing = 8, .stagger = false});
  EXPECT_EQ(f.cubemap.TexelOf(regular.Anchor(3, 5)).x % 8, 0);
}

TEST(RefinePlanTest, StartSpacingIsAPowerOfTwoUpToAnEighthOfN) {
  const Fixture f(64);
  EXPECT_EQ(RefinePlan(f.cubemap, f.pattern, {.start_spacing = 6}).options().start_spacing, 4);
  EXPECT_EQ(RefinePlan(f.cubemap, f.pattern, {.start_spacing = 64}).options().start_spacing, 8);
  EXPECT_EQ(RefinePlan(f.cubemap, f.pattern, {.start_spacing = 0}).options().start_spacing, 1);
  const Fixture coarse(8);
  EXPECT_EQ(RefinePlan(coarse.cubemap, coarse.pattern, {}).options().start_spacing, 1);
}

}  // namespace
}  // namespace wavebake
