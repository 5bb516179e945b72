// The column size estimate (core/columns/coded_size.h) against entropies
// worked out by hand: n·log2 n − Σ c·log2 c per byte set.
#include "core/columns/coded_size.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace wavebake {
namespace {

TEST(CodedSizeTest, ConstantBytesCostNothing) {
  // Deltas 5,5,5 (first from 0) and all-zero codes: one byte value per set.
  const std::vector<uint32_t> positions = {5, 10, 15};
  const std::vector<int16_t> codes = {0, 0, 0};
  EXPECT_EQ(CodedBits(positions, codes), 0.0);
  EXPECT_EQ(CodedBits({}, {}), 0.0);
}

TEST(CodedSizeTest, DeltaPlanesAndCodeBytesAddTheirEntropies) {
  // Deltas 0,1,1,1: low plane counts {0: 1, 1: 3}, the upper planes zero.
  const std::vector<uint32_t> positions = {0, 1, 2, 3};
  // Bytes 1,0, 2,0, 3,0, 4,0: counts {0: 4, 1..4: 1}.
  const std::vector<int16_t> codes = {1, 2, 3, 4};
  const double index_bits = 4 * std::log2(4.0) - 3 * std::log2(3.0);
  const double code_bits = 8 * std::log2(8.0) - 4 * std::log2(4.0);
  EXPECT_NEAR(CodedBits(positions, codes), index_bits + code_bits, 1e-9);
}

TEST(CodedSizeTest, AHigherDeltaPlaneCountsOnceUsed) {
  // Deltas 0 and 256: low bytes 0,0 (0 bits), second bytes 0,1 (2 bits).
  EXPECT_NEAR(CodedBits(std::vector<uint32_t>{0, 256}, std::vector<int16_t>{0, 0}), 2.0, 1e-9);
  // Codes are little-endian two's complement: −1 is the bytes FF FF (one
  // value, 0 bits), 1 the bytes 01 00 (two values, 2 bits).
  EXPECT_EQ(CodedBits(std::vector<uint32_t>{0}, std::vector<int16_t>{-1}), 0.0);
  EXPECT_NEAR(CodedBits(std::vector<uint32_t>{0}, std::vector<int16_t>{1}), 2.0, 1e-9);
}

}  // namespace
}  // namespace wavebake
