// RelightMagnitude (runtime/gpu/relight_magnitude.h), the size of Eq. 8's
// sum that bounds the GPU mode's rounding: analytic on one coefficient (a
// Haar synthesis function of depth d is ±2^−d on its 2^d × 2^d support, for
// the 2D orthonormal step's factor ½ per step), and never below |B| of the
// CPU relighter on a real matrix (the triangle inequality).
#include "runtime/gpu/relight_magnitude.h"

#include <gtest/gtest.h>

#include <cmath>

#include "relight_fixtures.h"
#include "runtime/relight/relighter.h"

namespace wavebake {
namespace {

CompressedColumns OneCoefficient(int depth, uint32_t position, float value) {
  CompressedColumns t;
  t.width = t.height = 16;
  t.light_res = 1;
  t.columns = 6;
  t.indptr = {0, 1, 1, 1, 1, 1, 1};
  t.indices = {position};
  t.values = {value};
  t.depth = {uint8_t(depth), 0, 0, 0, 0, 0};
  return t;
}

TEST(RelightMagnitude, OneDetailCoefficientCoversItsSupportWithTwoToMinusDepth) {
  // Depth 2 on 16×16: the HH detail of step 1 (the 8×8 block) at (1, 0)
  // of its 4×4 quarter sits at x = 4 + 1, y = 4 + 0; step 1's inverse
  // spreads it over x 2..3, y 0..1 (×½), step 0's over x 4..7, y 0..3 (×¼).
  const CompressedColumns t = OneCoefficient(2, 4 * 16 + 5, -3.0f);
  const WaveletLight light{0, {1.0f, 0.5f, -2.0f}};
  absl::StatusOr<std::vector<float>> m = RelightMagnitude(t, std::span(&light, 1));
  ASSERT_TRUE(m.ok()) << m.status();
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool inside = x >= 4 && x < 8 && y < 4;
      for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ((*m)[3 * (y * 16 + x) + c],
                        inside ? 3.0f * std::fabs(light.weight[c]) / 4 : 0)
            << x << "," << y << " c" << c;
    }
}

TEST(RelightMagnitude, BoundsTheRelighterAndRefusesOtherFilters) {
  testing::MiniBakeOptions o;
  o.width = o.height = 16;
  o.light_res = 4;
  const testing::MiniBake bake = testing::RunMiniBake(o);
  absl::StatusOr<Relighter> r = Relighter::Create(bake.compressed, bake.samples);
  ASSERT_TRUE(r.ok()) << r.status();
  WaveletLights lights;
  lights.light_res = 4;
  for (uint32_t m = 0; m < uint32_t(bake.compressed.columns); m += 3)
    lights.lights.push_back({m, {1.0f - 0.01f * m, 0.3f, m % 2 ? -0.5f : 0.5f}});
  std::vector<float> b(3 * 256);
  r->RelightTransport(lights.lights, b);
  absl::StatusOr<std::vector<float>> m = RelightMagnitude(bake.compressed, lights.lights);
  ASSERT_TRUE(m.ok()) << m.status();
  int strict = 0;
  for (size_t i = 0; i < b.size(); ++i) {
    EXPECT_GE((*m)[i], std::fabs(b[i]) * (1 - 1e-5f)) << i;
    strict += (*m)[i] > std::fabs(b[i]) * 1.01f;
  }
  EXPECT_GT(strict, 0) << "signs cancel somewhere, so M exceeds |B| somewhere";
  CompressedColumns other = bake.compressed;
  other.column_filter = WaveletFilter::kLeGall53;
  absl::StatusOr<std::vector<float>> refused = RelightMagnitude(other, lights.lights);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("column_filter"), std::string::npos);
}

}  // namespace
}  // namespace wavebake
