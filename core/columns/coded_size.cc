#include "core/columns/coded_size.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace wavebake {
namespace {

// c·log2 c, from a table for the small counts most bins hold: a log2 per
// occupied bin cost as much as the rest of the estimate.
double CLogC(uint32_t c) {
  constexpr uint32_t kTable = 4096;
  static const std::vector<double> table = [] {
    std::vector<double> t(kTable);
    for (uint32_t i = 1; i < kTable; ++i) t[i] = i * std::log2(double(i));
    return t;
  }();
  return c < kTable ? table[c] : c * std::log2(double(c));
}

// n·H(bytes) = n·log2 n − Σ_b c_b·log2 c_b over one byte histogram.
class ByteHistogram {
 public:
  void Add(uint8_t b) { ++count_[b]; }
  double Bits(uint32_t n) const {
    double sum = CLogC(n);
    for (uint32_t c : count_) sum -= CLogC(c);
    return sum;
  }

 private:
  std::array<uint32_t, 256> count_{};
};

}  // namespace

double CodedBits(std::span<const uint32_t> positions, std::span<const int16_t> codes) {
  ByteHistogram values;
  for (int16_t c : codes) {
    const auto u = static_cast<uint16_t>(c);
    values.Add(uint8_t(u));
    values.Add(uint8_t(u >> 8));
  }
  double bits = values.Bits(2 * uint32_t(codes.size()));
  // Planes above the largest delta's top byte hold zeros only: 0 bits.
  uint32_t largest = 0, previous = 0;
  for (uint32_t p : positions) largest = std::max(largest, p - previous), previous = p;
  for (int k = 0; k < 4 && (k == 0 || (largest >> (8 * k)) != 0); ++k) {
    ByteHistogram plane;
    previous = 0;
    for (uint32_t p : positions) {
      plane.Add(uint8_t((p - previous) >> (8 * k)));  // the delta filter, from 0 for the first
      previous = p;
    }
    bits += plane.Bits(uint32_t(positions.size()));
  }
  return bits;
}

}  // namespace wavebake
