#include "core/bake/bake_gather.h"

#include <gtest/gtest.h>

#include <vector>

namespace wavebake {
namespace {

// An operator from hand-written rows (sources only; weights 1).
BounceGather Rows(int sources, const std::vector<std::vector<int32_t>>& rows) {
  BounceGather g;
  g.cells = static_cast<int>(rows.size());
  g.sources = sources;
  g.offsets.push_back(0);
  for (const auto& r : rows) {
    g.source.insert(g.source.end(), r.begin(), r.end());
    g.weight.insert(g.weight.end(), r.size(), 1.0f);
    g.offsets.push_back(static_cast<int64_t>(g.source.size()));
  }
  return g;
}

// Two pixels read vertices 0 and 1; among the vertices 0 reads 2, 2 reads 3,
// 3 reads 4, and 5 (which nothing reads) reads 0. B bounces read the rows
// that G_ca and B − 1 hops of G_aa reach, never vertex 5's.
TEST(MarkAuxRowsTest, MarksWhatTheBouncesRead) {
  BakeGathers g;
  g.aux.width = 6;
  g.aux.height = 1;
  g.aux.position.assign(6, Vec3{});
  g.aux.grid = {0, 1, 2, 3, 4, 5};
  g.gather = Rows(6, {{0}, {1}});
  g.aux_gather = Rows(6, {{2}, {}, {3}, {4}, {}, {0}});
  const std::vector<std::vector<uint8_t>> expected = {
      {1, 1, 0, 0, 0, 0}, {1, 1, 1, 0, 0, 0}, {1, 1, 1, 1, 0, 0}, {1, 1, 1, 1, 1, 0}};
  for (int b = 1; b <= 4; ++b) {
    MarkAuxRows(b, g);
    EXPECT_EQ(g.aux_rows, expected[b - 1]) << b << " bounces";
  }
  MarkAuxRows(8, g);
  EXPECT_EQ(g.aux_rows, expected[3]);
  MarkAuxRows(0, g);
  EXPECT_EQ(g.aux_rows, std::vector<uint8_t>(6, 0));
}

// Without an auxiliary set (mesh and lightmap layouts) nothing is marked.
TEST(MarkAuxRowsTest, NoAuxiliarySetNoMarks) {
  BakeGathers g;
  g.gather = Rows(2, {{0}, {1}});
  MarkAuxRows(3, g);
  EXPECT_TRUE(g.aux_rows.empty());
}

}  // namespace
}  // namespace wavebake
