// The uv layout (core/layouts/layout.h UvLayout, core/layouts/uv_atlas.h): which texels a UV
// atlas covers, where their samples lie, and the errors of atlases that are
// no lightmap. Expected texels and positions come from the geometry of the
// test meshes, not from the rasterizer.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "core/layouts/layout.h"
#include "core/layouts/uv_atlas.h"
#include "core/scene/scene_check.h"
#include "tests/core/test_shapes.h"

namespace wavebake {
namespace {

using test_shapes::SceneOf;
using ::testing::HasSubstr;

// The unit square z = 0 facing +z, UV = (x, y) mapped into [lo, hi]².
Mesh UvQuad(std::string name, float lo, float hi, Vec3 offset = {}) {
  Mesh m;
  m.name = std::move(name);
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (Vec3& p : m.positions) p = p + offset;
  m.normals.assign(4, {0, 0, 1});
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.uv_channels = {{{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}}};
  return m;
}

LayoutSpec Uv(int side, std::string_view options = "") {
  return *ParseLayout("uv:" + std::to_string(side) + "x" + std::to_string(side) +
                      std::string(options));
}

TEST(ParseLayout, UvForms) {
  const LayoutSpec d = *ParseLayout("uv");
  EXPECT_EQ(d.kind, LayoutKind::kUv);
  EXPECT_EQ(d.width, 256);
  EXPECT_EQ(d.height, 256);
  EXPECT_EQ(d.uv_channel, 0);
  EXPECT_FALSE(d.allow_uv_overlap);
  EXPECT_EQ(d.fill, kDefaultUvFill);
  const LayoutSpec o = *ParseLayout("uv1:64x32,allow-overlap,fill=zero");
  EXPECT_EQ(o.uv_channel, 1);
  EXPECT_EQ(o.width, 64);
  EXPECT_EQ(o.height, 32);
  EXPECT_TRUE(o.allow_uv_overlap);
  EXPECT_EQ(o.fill, UncoveredFill::kZero);
  for (const char* spec : {"uv:256x256", "uv1:64x32,allow-overlap,fill=zero", "uv:8x8,fill=dilate"})
    EXPECT_EQ(ToString(*ParseLayout(spec)), spec);
  EXPECT_THAT(ParseLayout("uv:64x64,fill=blur").status().message(), HasSubstr("fill=blur"));
  EXPECT_THAT(ParseLayout("hilbert:64x64,allow-overlap").status().message(),
              HasSubstr("no options"));
  EXPECT_THAT(ParseLayout("uv:48x48").status().message(), HasSubstr("power of two"));
}

TEST(UvLayout, QuadCoversExactlyTheTexelsItsUvsTouch) {
  // UVs [0.1, 0.9] at 16²: x and y from 1.6 to 14.4 texels, so texels 1..14
  // are covered (conservatively: 1 and 14 only in part) and no others.
  Scene scene = SceneOf({UvQuad("quad", 0.1f, 0.9f)});
  const absl::StatusOr<SampleSet> s = UvLayout(scene, Uv(16));
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ(s->size(), 14 * 14);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const int32_t id = s->grid[y * 16 + x];
      const bool inside = x >= 1 && x <= 14 && y >= 1 && y <= 14;
      ASSERT_EQ(id >= 0, inside) << x << "," << y;
      if (!inside) continue;
      // Texel centre (x+.5, y+.5) is UV u = (x+.5)/16, v = 1 − (y+.5)/16 and
      // so quad point ((u − .1)/.8, (v − .1)/.8), clamped onto the quad for
      // the border texels whose centre lies outside it.
      auto coord = [](double t) { return std::clamp((t - 0.1) / 0.8, 0.0, 1.0); };
      const Vec3 p = s->position[id];
      EXPECT_NEAR(p.x, coord((x + 0.5) / 16), 1e-5) << x << "," << y;
      EXPECT_NEAR(p.y, coord(1 - (y + 0.5) / 16), 1e-5) << x << "," << y;
      EXPECT_EQ(p.z, 0);
      EXPECT_EQ(s->normal[id], (Vec3{0, 0, 1}));
    }
  }
  ASSERT_EQ(s->uv_charts.size(), 1u);
  EXPECT_EQ(s->uv_charts[0].width, 16);
  EXPECT_EQ(s->uv_charts[0].mesh, "quad");
}

TEST(UvLayout, ChartThinnerThanATexelKeepsItsTexels) {
  // A strip 0.3 texels tall across row 5 of a 16² lightmap, between the row's
  // texel centres (y in [5.6, 5.9]): no centre is inside, every texel of the
  // row that the strip crosses (x from 2 to 12) must still be covered.
  Mesh strip;
  strip.name = "strip";
  strip.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0.1f, 0}, {0, 0.1f, 0}};
  strip.normals.assign(4, {0, 0, 1});
  strip.triangles = {{0, 1, 2}, {0, 2, 3}};
  const float v_lo = 1 - 5.9f / 16, v_hi = 1 - 5.6f / 16;
  const float u_lo = 2.2f / 16, u_hi = 12.7f / 16;
  strip.uv_channels = {{{u_lo, v_lo}, {u_hi, v_lo}, {u_hi, v_hi}, {u_lo, v_hi}}};
  const absl::StatusOr<SampleSet> s = UvLayout(SceneOf({strip}), Uv(16));
  ASSERT_TRUE(s.ok()) << s.status();
  std::set<std::pair<int, int>> covered;
  for (int c = 0; c < 256; ++c)
    if (s->grid[c] >= 0) covered.insert({c % 16, c / 16});
  std::set<std::pair<int, int>> expected;
  for (int x = 2; x <= 12; ++x) expected.insert({x, 5});
  EXPECT_EQ(covered, expected);
  for (int id = 0; id < s->size(); ++id) {  // clamped onto the strip
    EXPECT_GE(s->position[id].y, 0);
    EXPECT_LE(s->position[id].y, 0.1f + 1e-6f);
  }
}

TEST(UvLayout, OverlappingChartsAreAnErrorNamingMeshAndFraction) {
  // A second triangle elsewhere in space (z = 1) with the UVs of the
  // quad's first: every texel centre of that lower-right half lies inside both.
  Mesh folded = UvQuad("folded", 0, 1);
  folded.triangles = {{0, 1, 2}, {4, 5, 6}};
  for (uint32_t v : {0, 1, 2}) {
    folded.positions.push_back(folded.positions[v] + Vec3{0, 0, 1});
    folded.normals.push_back({0, 0, 1});
    folded.uv_channels[0].push_back(folded.uv_channels[0][v]);
  }
  const absl::StatusOr<SampleSet> s = UvLayout(SceneOf({folded}), Uv(8));
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.status().message(), HasSubstr("'folded'"));
  EXPECT_THAT(s.status().message(), HasSubstr("overlapping UVs"));
  // In texels the half is x + y ≥ 8 (row 0 at the top): 28 centres strictly
  // inside (x + y ≥ 8), 36 texels covered (x + y ≥ 7).
  EXPECT_THAT(s.status().message(), HasSubstr("77.78 %"));
  EXPECT_TRUE(UvLayout(SceneOf({folded}), Uv(8, ",allow-overlap")).ok());
}

TEST(UvLayout, MeshWithoutUvsIsAnErrorSuggestingHilbert) {
  Mesh bare = UvQuad("bare", 0, 1);
  bare.uv_channels.clear();
  const absl::StatusOr<SampleSet> s = UvLayout(SceneOf({UvQuad("ok", 0, 1), bare}), Uv(8));
  ASSERT_FALSE(s.ok());
  EXPECT_THAT(s.status().message(), HasSubstr("mesh 'bare' has no UV channel 0"));
  EXPECT_THAT(s.status().message(), HasSubstr("hilbert"));
  const absl::StatusOr<SampleSet> one =
      UvLayout(SceneOf({UvQuad("ok", 0, 1)}), *ParseLayout("uv1:8x8"));
  EXPECT_THAT(one.status().message(), HasSubstr("no UV channel 1 (it has 1)"));
}

TEST(UvLayout, EveryMeshGetsItsOwnRectangle) {
  // Areas 1 : 3 of a 64² lightmap: shares 1024 and 3072 texels, so 32² for
  // both (a 64² square does not fit beside another); equal squares go in mesh
  // order along the Z order: (0,0), then (32,0).
  Mesh big = UvQuad("big", 0, 1);
  for (Vec3& p : big.positions) p = {p.x * 3, p.y, p.z};
  Scene scene = SceneOf({UvQuad("small", 0, 1, {0, 0, 2}), big});
  const absl::StatusOr<SampleSet> s = UvLayout(scene, Uv(64));
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_EQ(s->uv_charts.size(), 2u);
  const UvChart& small = s->uv_charts[0];
  const UvChart& large = s->uv_charts[1];
  EXPECT_EQ((std::array{small.x, small.y, small.width, small.height}), (std::array{0, 0, 32, 32}));
  EXPECT_EQ((std::array{large.x, large.y, large.width, large.height}), (std::array{32, 0, 32, 32}));
  // Each mesh's samples lie in its rectangle: the small quad sits at z = 2.
  for (int c = 0; c < 64 * 64; ++c) {
    const int32_t id = s->grid[c];
    if (id < 0) continue;
    const bool in_small = c % 64 < 32 && c / 64 < 32;
    EXPECT_EQ(s->position[id].z == 2, in_small) << c;
  }
  EXPECT_EQ(s->size(), 2 * 32 * 32);
}

TEST(PackCharts, PowerOfTwoSquaresWithoutOverlap) {
  const std::vector<double> areas{5, 1, 1, 0.2, 3, 0.01};
  const absl::StatusOr<std::vector<TexelRect>> rects = PackCharts(areas, 128, 64);
  ASSERT_TRUE(rects.ok());
  std::vector<int> owner(128 * 64, -1);
  for (size_t i = 0; i < rects->size(); ++i) {
    const TexelRect& r = (*rects)[i];
    EXPECT_EQ(r.width, r.height);
    EXPECT_EQ(r.width & (r.width - 1), 0) << r.width;
    for (int y = r.y; y < r.y + r.height; ++y)
      for (int x = r.x; x < r.x + r.width; ++x) {
        ASSERT_TRUE(x < 128 && y < 64);
        EXPECT_EQ(owner[y * 128 + x], -1) << "mesh " << i << " overlaps at " << x << "," << y;
        owner[y * 128 + x] = int(i);
      }
  }
  EXPECT_GE((*rects)[0].width, (*rects)[4].width);  // larger area, no smaller square
}

}  // namespace
}  // namespace wavebake
