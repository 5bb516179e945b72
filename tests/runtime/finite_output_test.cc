// Every numeric result is finite or an error: the relit-image check
// (runtime/relight/finite_output.h) and the error measures (runtime/reference/eval.h).
#include "runtime/relight/finite_output.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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

}  // namespace
}  // namespace wavebake
