// Eq. 8 relighting (runtime/relight/relighter.h) against its oracles: Eq. 3 (every
// column inverse-transformed on its own), the dense product, and exact
// reconstruction of known pixel-domain columns.
#include "runtime/relight/relighter.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>

#include "core/wavelets/wavelet2d.h"
#include "runtime/reference/relight_oracles.h"
#include "tests/runtime/relight_fixtures.h"

namespace wavebake {
// Counts every heap allocation of this test binary, so a test can assert
// that a frame allocates nothing (the replacement is global but harmless).
std::atomic<int64_t> g_allocations{0};

}  // namespace wavebake

// GCC sees malloc'd memory reach the replaced delete after inlining and
// warns; the pair is consistent (both malloc/free).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  ++wavebake::g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace wavebake {
namespace {

using testing::Compare;
using testing::RandomColumns;
using testing::RandomSamples;

WaveletLights RandomLights(int light_res, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> column(0, 6 * light_res * light_res - 1);
  std::uniform_real_distribution<float> w(-2, 2);
  WaveletLights l{light_res, {}};
  for (int i = 0; i < count; ++i) l.lights.push_back({column(rng), {w(rng), w(rng), w(rng)}});
  l.lights.push_back(l.lights.front());  // a repeated column adds twice
  return l;
}

double MaxAbsFinite(const std::vector<float>& v) {
  double m = 0;
  for (float x : v)
    if (!std::isnan(x)) m = std::max(m, std::fabs(double{x}));
  return m;
}

struct GridCase {
  WaveletFilter filter;
  int width, height;
};

void PrintTo(const GridCase& g, std::ostream* os) {
  *os << "filter " << static_cast<int>(g.filter) << " " << g.width << "x" << g.height;
}

std::string GridCaseName(const ::testing::TestParamInfo<GridCase>& info) {
  const char* names[] = {"haar", "daub4", "legall53", "cdf97"};
  return std::string(names[static_cast<int>(info.param.filter)]) + "_" +
         std::to_string(info.param.width) + "x" + std::to_string(info.param.height);
}

class Eq8VersusNaive : public ::testing::TestWithParam<GridCase> {};

// Eq. 8 (grouped by depth, one single-step inverse between groups) is the
// same linear map as Eq. 3: equal to float precision for every filter, square
// and non-square grids, random depths 0..MaxDepth, repeated columns.
TEST_P(Eq8VersusNaive, SameImage) {
  const GridCase g = GetParam();
  const CompressedColumns t = RandomColumns(g.width, g.height, 4, g.filter, 40, 7);
  const SampleSet samples = RandomSamples(g.width, g.height, 0.2, 3);
  auto relighter = Relighter::Create(t, samples);
  ASSERT_TRUE(relighter.ok()) << relighter.status();
  const WaveletLights lights = RandomLights(4, 60, 11);
  std::vector<float> fast(3 * samples.cells()), slow(fast.size());
  relighter->Relight(lights, fast);
  NaiveRelight(t, CellAlbedo(samples), lights.lights, slow);
  const double scale = MaxAbsFinite(slow);
  ASSERT_GT(scale, 0.1);
  EXPECT_LT(Compare(fast, slow).max_abs, 2e-6 * scale);
  for (int cell = 0; cell < samples.cells(); ++cell) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(std::isnan(fast[3 * cell + c]), samples.grid[cell] < 0) << cell;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllFilters, Eq8VersusNaive,
                         ::testing::Values(GridCase{WaveletFilter::kHaar, 32, 32},
                                           GridCase{WaveletFilter::kHaar, 64, 16},
                                           GridCase{WaveletFilter::kDaub4, 32, 32},
                                           GridCase{WaveletFilter::kLeGall53, 32, 32},
                                           GridCase{WaveletFilter::kLeGall53, 16, 64},
                                           GridCase{WaveletFilter::kCdf97, 32, 32},
                                           GridCase{WaveletFilter::kCdf97, 64, 32}),
                         GridCaseName);

// Perfect reconstruction: pixel-domain columns forward-transformed to random
// depths with every coefficient kept relight to Σ w_m P_m computed in double
// from the original pixels (no inverse transform in the oracle at all).
TEST(Relighter, ReconstructsKnownPixelColumns) {
  for (WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kLeGall53, WaveletFilter::kCdf97}) {
    const int w = 32, h = 16, n = 2, cols = 6 * n * n;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1, 1);
    std::uniform_int_distribution<int> depth(0, MaxDepth(w, h));
    CompressedColumns t;
    t.width = w, t.height = h, t.light_res = n, t.columns = cols, t.column_filter = f;
    t.indptr.push_back(0);
    std::vector<std::vector<float>> pixels(cols);
    for (int m = 0; m < cols; ++m) {
      pixels[m].resize(w * h);
      for (float& v : pixels[m]) v = u(rng);
      std::vector<float> img = pixels[m];
      const int d = depth(rng);
      Forward2d(f, img, w, h, d);
      for (int p = 0; p < w * h; ++p) {
        t.indices.push_back(p);
        t.values.push_back(img[p]);
      }
      t.indptr.push_back(static_cast<int64_t>(t.indices.size()));
      t.depth.push_back(static_cast<uint8_t>(d));
    }
    const SampleSet samples = RandomSamples(w, h, 0.0, 9);
    const std::vector<float> albedo = CellAlbedo(samples);
    WaveletLights lights{n, {}};
    for (int m = 0; m < cols; ++m) {
      lights.lights.push_back({static_cast<uint32_t>(m), {u(rng), u(rng), u(rng)}});
    }
    std::vector<float> expect(3 * w * h);
    for (int p = 0; p < w * h; ++p) {
      for (int c = 0; c < 3; ++c) {
        double s = 0;
        for (int m = 0; m < cols; ++m) s += double{lights.lights[m].weight[c]} * pixels[m][p];
        expect[3 * p + c] = static_cast<float>(s * albedo[3 * p + c]);
      }
    }
    auto relighter = Relighter::Create(t, samples);
    ASSERT_TRUE(relighter.ok());
    std::vector<float> got(expect.size());
    relighter->Relight(lights, got);
    EXPECT_LT(Compare(got, expect).max_abs, 1e-4) << static_cast<int>(f);
  }
}

// With every column as a light, Eq. 8 equals the dense matrix-vector product
// of the decoded matrix.
TEST(Relighter, AllLightsEqualDenseProduct) {
  const CompressedColumns t = RandomColumns(32, 32, 4, WaveletFilter::kLeGall53, 30, 21);
  const SampleSet samples = RandomSamples(32, 32, 0.1, 4);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0, 1);
  LightingCoefficients l{4, WaveletFilter::kHaar, std::vector<float>(3 * t.columns)};
  for (float& v : l.rgb) v = u(rng);
  auto relighter = Relighter::Create(t, samples);
  ASSERT_TRUE(relighter.ok());
  std::vector<float> eq8(3 * samples.cells()), dense(eq8.size());
  relighter->Relight(AllWaveletLights(l), eq8);
  DenseRelight(Densify(t), l.rgb, CellAlbedo(samples), dense);
  EXPECT_LT(Compare(eq8, dense).rel_rms, 1e-5);
}

// "No allocation per frame": once the scratch has grown (first frame), a
// frame with as many lights allocates nothing, for every filter.
TEST(Relighter, SteadyStateFramesDoNotAllocate) {
  for (WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4, WaveletFilter::kLeGall53,
                          WaveletFilter::kCdf97}) {
    const CompressedColumns t = RandomColumns(64, 32, 4, f, 50, 3);
    const SampleSet samples = RandomSamples(64, 32, 0.1, 5);
    auto relighter = Relighter::Create(t, samples);
    ASSERT_TRUE(relighter.ok());
    const WaveletLights a = RandomLights(4, 90, 1), b = RandomLights(4, 90, 2);
    std::vector<float> out(3 * samples.cells());
    relighter->Relight(a, out);
    const int64_t before = g_allocations.load();
    relighter->Relight(b, out);
    relighter->Relight(a, out);
    EXPECT_EQ(g_allocations.load(), before) << static_cast<int>(f);
  }
}

TEST(Relighter, NoLightsGiveBlackAndMaskedNaN) {
  const CompressedColumns t = RandomColumns(16, 16, 2, WaveletFilter::kHaar, 10, 1);
  const SampleSet samples = RandomSamples(16, 16, 0.3, 2);
  auto relighter = Relighter::Create(t, samples);
  ASSERT_TRUE(relighter.ok());
  std::vector<float> out(3 * 256, 5.0f);
  relighter->Relight(WaveletLights{2, {}}, out);
  for (int cell = 0; cell < 256; ++cell) {
    if (samples.grid[cell] < 0) {
      EXPECT_TRUE(std::isnan(out[3 * cell]));
    } else {
      EXPECT_EQ(out[3 * cell], 0.0f);
    }
  }
}

TEST(Relighter, RejectsInconsistentMatrices) {
  const CompressedColumns good = RandomColumns(16, 16, 2, WaveletFilter::kHaar, 10, 1);
  const SampleSet samples = RandomSamples(16, 16, 0.0, 2);
  ASSERT_TRUE(Relighter::Create(good, samples).ok());
  auto expect_error = [&](CompressedColumns t, const char* field) {
    auto r = Relighter::Create(t, samples);
    ASSERT_FALSE(r.ok()) << field;
    EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find(field), std::string_view::npos) << r.status();
  };
  CompressedColumns t = good;
  t.indices[3] = 256;
  expect_error(t, "transport/indices");
  t = good;
  t.depth[5] = 5;  // MaxDepth(16, 16) = 4
  expect_error(t, "transport/depth");
  t = good;
  std::swap(t.indptr[3], t.indptr[4]);
  expect_error(t, "transport/indptr");
  t = good;
  t.columns = 25;
  expect_error(t, "columns");
  t = good;
  t.values.pop_back();
  expect_error(t, "values");
  SampleSet other = RandomSamples(32, 8, 0.0, 2);
  auto r = Relighter::Create(good, other);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("samples"), std::string_view::npos);
}

}  // namespace
}  // namespace wavebake
