#include "core/layouts/layout.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "core/layouts/layout_hilbert_curve.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_check.h"
#include "tests/core/scene_testing.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

Scene Checked(const std::string& name) {
  Scene s = *MakeBuiltinScene(name);
  EXPECT_TRUE(CheckAndRepairScene(s, nullptr).ok());
  return s;
}

TEST(ParseLayout, AcceptsTheThreeForms) {
  const auto camera = ParseLayout("camera");
  ASSERT_TRUE(camera.ok());
  EXPECT_EQ(camera->kind, LayoutKind::kCamera);
  EXPECT_EQ(camera->width, 64);
  EXPECT_EQ(camera->height, 64);
  const auto wide = ParseLayout("camera:128x32");
  ASSERT_TRUE(wide.ok());
  EXPECT_EQ(wide->width, 128);
  EXPECT_EQ(wide->height, 32);
  const auto grid = ParseLayout("grid");
  ASSERT_TRUE(grid.ok());
  EXPECT_EQ(grid->kind, LayoutKind::kGrid);
  const auto hilbert = ParseLayout("hilbert:4096x1");
  ASSERT_TRUE(hilbert.ok());
  EXPECT_EQ(hilbert->kind, LayoutKind::kHilbert);
  EXPECT_EQ(hilbert->width, 4096);
  EXPECT_EQ(hilbert->height, 1);
}

TEST(ParseLayout, ToStringReadsBack) {
  for (const char* spec : {"camera:64x64", "grid", "hilbert:128x64", "camera:1x2"}) {
    const auto parsed = ParseLayout(spec);
    ASSERT_TRUE(parsed.ok()) << spec;
    EXPECT_EQ(ToString(*parsed), spec);
  }
}

TEST(ParseLayout, ErrorsNameTheLayoutField) {
  const std::pair<const char*, const char*> cases[] = {{"hilbert", "needs a size"},
                                                       {"hilbert:63x64", "power of two"},
                                                       {"hilbert:64x8192", "power of two"},
                                                       {"camera:0x4", "power of two"},
                                                       {"camera:64", "WxH"},
                                                       {"camera:64x", "WxH"},
                                                       {"camera:axb", "WxH"},
                                                       {"hilbert:-64x64", "power of two"},
                                                       {"hilbert: 64x64", "WxH"},
                                                       {"grid:64x64", "grid mesh"},
                                                       {"spiral", "camera[:WxH]"},
                                                       {"", "camera[:WxH]"}};
  for (const auto& [spec, why] : cases) {
    const auto parsed = ParseLayout(spec);
    ASSERT_FALSE(parsed.ok()) << spec;
    EXPECT_EQ(parsed.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(parsed.status().message(), HasSubstr("layout"));
    EXPECT_THAT(parsed.status().message(), HasSubstr(why)) << spec;
  }
}

// The 2D curve visits every cell once, and consecutive cells share an edge.
TEST(HilbertCurve, IsAnEdgeConnectedBijectionForSquareWideAndTallGrids) {
  for (auto [w, h] :
       {std::pair{1, 1}, {2, 2}, {8, 8}, {64, 64}, {16, 4}, {4, 16}, {32, 1}, {1, 8}}) {
    const std::vector<int32_t> cells = HilbertCurveCells(w, h);
    ASSERT_EQ(cells.size(), static_cast<size_t>(w * h));
    EXPECT_EQ(std::set<int32_t>(cells.begin(), cells.end()).size(), cells.size());
    for (size_t t = 1; t < cells.size(); ++t) {
      const int dx = std::abs(cells[t] % w - cells[t - 1] % w);
      const int dy = std::abs(cells[t] / w - cells[t - 1] / w);
      ASSERT_EQ(dx + dy, 1) << w << "x" << h << " at " << t;
    }
  }
}

// The 3D key orders the cube's cells along a curve of face-adjacent steps.
TEST(HilbertCurve, Key3IsAFaceConnectedBijection) {
  for (int bits : {1, 2, 3, 4}) {
    const uint32_t n = 1u << bits;
    std::vector<std::array<int, 3>> at(n * n * n, {-1, -1, -1});
    for (uint32_t x = 0; x < n; ++x)
      for (uint32_t y = 0; y < n; ++y)
        for (uint32_t z = 0; z < n; ++z) {
          const uint64_t k = HilbertKey3(x, y, z, bits);
          ASSERT_LT(k, at.size());
          ASSERT_EQ(at[k][0], -1) << "key " << k << " twice";
          at[k] = {int(x), int(y), int(z)};
        }
    for (size_t k = 1; k < at.size(); ++k) {
      const int d = std::abs(at[k][0] - at[k - 1][0]) + std::abs(at[k][1] - at[k - 1][1]) +
                    std::abs(at[k][2] - at[k - 1][2]);
      ASSERT_EQ(d, 1) << "bits " << bits << " key " << k;
    }
  }
}

TEST(GridLayout, FurnaceIsAFullImageOfItsVertexLattice) {
  const Scene s = Checked("furnace");
  const auto layout = GridLayout(s);
  ASSERT_TRUE(layout.ok()) << layout.status();
  EXPECT_EQ(layout->width, 64);
  EXPECT_EQ(layout->height, 64);
  bool bijective = false;
  EXPECT_EQ(testing_util::CheckBijection(*layout, &bijective), 0);
  EXPECT_TRUE(bijective);
  // Cells next to each other hold vertices one lattice step apart, along +X
  // for x and +Z for y.
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Vec3 p = layout->position[layout->grid[y * 64 + x]];
      if (x + 1 < 64) {
        const Vec3 d = layout->position[layout->grid[y * 64 + x + 1]] - p;
        EXPECT_EQ(d, (Vec3{builtin::kGroundSpacing, 0, 0}));
      }
      if (y + 1 < 64) {
        const Vec3 d = layout->position[layout->grid[(y + 1) * 64 + x]] - p;
        EXPECT_EQ(d, (Vec3{0, 0, builtin::kGroundSpacing}));
      }
    }
  for (int i = 0; i < layout->size(); ++i) {
    EXPECT_EQ(layout->normal[i], (Vec3{0, 1, 0}));
    EXPECT_EQ(layout->albedo[i], s.meshes[0].albedo);
    EXPECT_EQ(layout->position[i], s.meshes[0].positions[layout->vertex[i]]);
  }
}

TEST(GridLayout, VertexIdsCountEarlierMeshes) {
  Scene s = Checked("sphere-plane");
  std::swap(s.meshes[0], s.meshes[1]);  // the grid is now the second mesh
  const auto layout = GridLayout(s);
  ASSERT_TRUE(layout.ok());
  const int32_t offset = static_cast<int32_t>(s.meshes[0].positions.size());
  for (int i = 0; i < layout->size(); ++i) {
    EXPECT_EQ(layout->vertex[i], offset + i);
    EXPECT_EQ(layout->position[i], s.meshes[1].positions[i]);
    EXPECT_EQ(layout->albedo[i], s.meshes[1].albedo);
  }
}

TEST(GridLayout, ErrorsNameTheLayout) {
  Scene none = Checked("sphere-plane");
  none.meshes.erase(none.meshes.begin());
  EXPECT_THAT(GridLayout(none).status().message(), HasSubstr("layout 'grid'"));
  Scene odd;
  Mesh m;
  m.name = "nine";
  m.grid_width = m.grid_height = 3;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.positions.push_back({float(i), 0, float(j)});
  m.normals.assign(9, {0, 1, 0});
  odd.meshes.push_back(m);
  const absl::Status st = GridLayout(odd).status();
  EXPECT_THAT(st.message(), HasSubstr("layout 'grid'"));
  EXPECT_THAT(st.message(), HasSubstr("nine"));
  EXPECT_THAT(st.message(), HasSubstr("power"));
}

TEST(HilbertLayout, CoversEveryVertexOnceAndKeepsNeighboursClose) {
  const Scene s = Checked("sphere-plane");  // 4096 + 64·31 + 2 = 6082 vertices
  size_t vertices = 0;
  for (const Mesh& m : s.meshes) vertices += m.positions.size();
  for (auto [w, h] : {std::pair{128, 64}, {64, 128}, {128, 128}}) {
    const auto layout = HilbertLayout(s, w, h);
    ASSERT_TRUE(layout.ok()) << layout.status();
    ASSERT_EQ(static_cast<size_t>(layout->size()), vertices);
    bool bijective = false;
    EXPECT_EQ(testing_util::CheckBijection(*layout, &bijective),
              w * h - static_cast<int>(vertices));
    EXPECT_TRUE(bijective);
    const double ordered = testing_util::MeanNeighbourDistance(*layout, layout->grid);
    const double shuffled = testing_util::RandomNeighbourDistance(*layout);
    EXPECT_LT(ordered, 0.25 * shuffled) << w << "x" << h;
  }
}

TEST(HilbertLayout, SamplesCarryTheirVertexAttributes) {
  const Scene s = Checked("disk-over-plane");
  const auto layout = HilbertLayout(s, 128, 64);
  ASSERT_TRUE(layout.ok());
  const Mesh& ground = s.meshes[0];
  const Mesh& disk = s.meshes[1];
  for (int i = 0; i < layout->size(); ++i) {
    EXPECT_EQ(layout->vertex[i], i);
    const bool on_ground = i < static_cast<int>(ground.positions.size());
    const Mesh& m = on_ground ? ground : disk;
    const size_t local = on_ground ? i : i - ground.positions.size();
    EXPECT_EQ(layout->position[i], m.positions[local]);
    EXPECT_EQ(layout->normal[i], m.normals[local]);
    EXPECT_EQ(layout->albedo[i], m.albedo);
  }
}

TEST(HilbertLayout, TooFewCellsOrBadSizesAreErrorsNamingTheLayout) {
  const Scene s = Checked("furnace");  // 4096 vertices
  EXPECT_TRUE(HilbertLayout(s, 64, 64).ok());
  const absl::Status small = HilbertLayout(s, 64, 32).status();
  EXPECT_EQ(small.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(small.message(), HasSubstr("hilbert:64x32"));
  EXPECT_THAT(small.message(), HasSubstr("4096 vertices"));
  EXPECT_THAT(HilbertLayout(s, 96, 64).status().message(), HasSubstr("power"));
}

}  // namespace
}  // namespace wavebake
