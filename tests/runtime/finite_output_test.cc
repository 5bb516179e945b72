// Every numeric result is finite or an error: the relit-image check
// (runtime/relight/finite_output.h) and the error measures (runtime/reference/eval.h).
#include "runtime/relight/finite_output.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "runtime/reference/eval.h"

namespace wavebake {
namespace {

using ::testing::HasSubstr;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(CheckRelitFinite, MaskedNaNIsFineAnyOtherNonFiniteValueIsNamed) {
  // 2×2 grid, cell 1 masked.
  const std::vector<int32_t> grid = {0, -1, 1, 2};
  std::vector<float> rgb = {1, 2, 3, kNaN, kNaN, kNaN, 0, 0, 0, 4, 5, 6};
  EXPECT_TRUE(CheckRelitFinite(rgb, grid, 2, "the environment").ok());
  for (float bad : {kNaN, kInf, -kInf}) {
    std::vector<float> broken = rgb;
    broken[3 * 3 + 2] = bad;  // cell 3 = (1, 1), channel B
    const absl::Status s = CheckRelitFinite(broken, grid, 2, "area light 'l.json'");
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_THAT(s.message(), HasSubstr("cell (1, 1) channel B"));
    EXPECT_THAT(s.message(), HasSubstr("area light 'l.json'"));
  }
}

// A NaN image used to score as identical: the NaN vanished in max() and in
// "sq > 0", giving rel_rms NaN (JSON null) and psnr +inf, and a NaN
// everywhere in the reference (an all-NaN "all lights" image) masked every
// cell, giving rel_rms 0 and psnr inf.
TEST(CompareToReference, NonFiniteValuesAreNeverAPerfectScore) {
  const std::vector<float> reference = {1, 1, 1, kNaN, kNaN, kNaN, 2, 2, 2};
  const std::vector<float> good = {1, 1, 1, kNaN, kNaN, kNaN, 2, 2, 2.5f};
  const ErrorStats fine = CompareToReference(good, reference);
  EXPECT_NEAR(fine.rel_rms, std::sqrt(0.25 / 15), 1e-12);
  absl::StatusOr<ErrorStats> checked = CompareFinite(good, reference, "the image");
  ASSERT_TRUE(checked.ok()) << checked.status();
  EXPECT_EQ(checked->rel_rms, fine.rel_rms);

  for (float bad : {kNaN, kInf}) {
    std::vector<float> image = good;
    image[7] = bad;
    const ErrorStats e = CompareToReference(image, reference);
    EXPECT_TRUE(std::isnan(e.rel_rms) && std::isnan(e.psnr) && std::isnan(e.max_abs)) << bad;
    const absl::Status s = CompareFinite(image, reference, "the compressed relighting").status();
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(s.message(), HasSubstr("the compressed relighting: value 1 of cell 2"));
    std::vector<float> ref = reference;
    ref[0] = kInf;  // an overflowed reference
    EXPECT_THAT(CompareFinite(good, ref, "x").status().message(), HasSubstr("the reference"));
  }
}

// 2^stops scales a relit image in float: FLT_MAX is just under 2^128 and the
// smallest normal float 2^-126, so ±126 stops are the widest that stay a
// finite, normal factor. A NaN exposure used to tone-map every pixel black
// and 200 stops to give inf (and inf × 0 = NaN) with rc 0.
TEST(CheckExposure, StopsWhoseFactorIsAFloatPassAnyOtherIsNamed) {
  for (double ok : {0.0, -3.5, 126.0, -126.0}) {
    EXPECT_TRUE(CheckExposure(ok).ok()) << ok;
    const float factor = static_cast<float>(std::exp2(ok));
    EXPECT_TRUE(std::isfinite(factor) && std::isnormal(factor)) << ok;
  }
  EXPECT_TRUE(std::isinf(static_cast<float>(std::exp2(128.0))));
  for (double bad : {127.0, -127.0, 200.0, double(kInf), -double(kInf), double(kNaN)}) {
    const absl::Status s = CheckExposure(bad);
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_THAT(std::string(s.message()), ::testing::StartsWith("exposure: ")) << bad;
  }
}

}  // namespace
}  // namespace wavebake
