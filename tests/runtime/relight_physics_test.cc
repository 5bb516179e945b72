// Relighting a real (mini-baked) transport matrix: the white furnace, the
// error against the dense T·L as the number of wavelet lights grows, and the
// compressed matrix meeting the bake's target error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "runtime/reference/relight_oracles.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/relighter.h"
#include "tests/runtime/relight_fixtures.h"

namespace wavebake {
namespace {

using testing::Compare;
using testing::DenseFromRows;
using testing::MiniBake;
using testing::MiniBakeOptions;
using testing::RunMiniBake;
using testing::SunAndSky;

const MiniBake& DiskBake() { return testing::SharedBake(MiniBakeOptions{}); }

std::vector<float> RelightWith(const MiniBake& b, const std::vector<float>& cube_rgb, int terms) {
  auto relighter = Relighter::Create(b.compressed, b.samples);
  EXPECT_TRUE(relighter.ok()) << relighter.status();
  const LightingCoefficients l =
      ProjectLighting(cube_rgb, b.compressed.light_res, WaveletFilter::kHaar);
  auto lights = SelectWaveletLights(l, terms);
  EXPECT_TRUE(lights.ok());
  std::vector<float> out(3 * b.samples.cells());
  relighter->Relight(*lights, out);
  return out;
}

// DESIGN.md §1: with L ≡ 1 and nothing occluding, B = albedo. The furnace
// scene's ground faces the whole upper hemisphere; the 6 scaling
// coefficients are the entire constant lighting, so 6 terms are exact.
TEST(RelightPhysics, WhiteFurnace) {
  MiniBakeOptions o;
  o.scene = "builtin:furnace";
  const MiniBake b = RunMiniBake(o);
  const int n = o.light_res;
  const std::vector<float> out = RelightWith(b, std::vector<float>(3 * 6 * n * n, 1.0f), 6);
  int checked = 0;
  for (int cell = 0; cell < b.samples.cells(); ++cell) {
    const int32_t id = b.samples.grid[cell];
    if (id < 0) continue;
    const Vec3 a = b.samples.albedo[id];
    EXPECT_NEAR(out[3 * cell] / a.x, 1.0, 0.01) << cell;
    EXPECT_NEAR(out[3 * cell + 1] / a.y, 1.0, 0.01) << cell;
    EXPECT_NEAR(out[3 * cell + 2] / a.z, 1.0, 0.01) << cell;
    ++checked;
  }
  EXPECT_GT(checked, b.samples.cells() / 2);
}

// More wavelet lights, less error against the dense, uncompressed T·L; with
// every light only the matrix compression (target 1 %) is left.
TEST(RelightPhysics, ErrorFallsWithTerms) {
  const MiniBake& b = DiskBake();
  const std::vector<float> cube = SunAndSky(8, 30);
  const std::vector<float> dense = DenseFromRows(b, cube);
  double previous = 1e9;
  for (int terms : {1, 4, 16, 64, 256, 384}) {
    const double err = Compare(RelightWith(b, cube, terms), dense).rel_rms;
    std::printf("terms %4d  rel_rms %.5f\n", terms, err);
    EXPECT_LE(err, previous * 1.0001 + 1e-7) << terms;
    previous = err;
  }
  EXPECT_LT(previous, 0.01);
}

// Without quantization, the kept coefficients are within target² · mean
// column energy of each column (DESIGN.md §1), so the decoded matrix is
// within target of the dense one in Frobenius norm; and relighting with every
// light matches the dense T·L to the same target, for several lightings.
TEST(RelightPhysics, AllLightsMatchDenseToTargetError) {
  const MiniBake& b = DiskBake();
  const DenseTransport decoded = Densify(b.compressed);
  double err = 0, energy = 0;
  const int cells = b.samples.cells();
  for (int m = 0; m < b.columns; ++m) {
    for (int i = 0; i < cells; ++i) {
      const double exact = b.wavelet_rows[static_cast<size_t>(i) * b.columns + m];
      const double d = decoded.values[static_cast<size_t>(m) * cells + i] - exact;
      err += d * d;
      energy += exact * exact;
    }
  }
  EXPECT_LE(std::sqrt(err / energy), 0.01 * 1.0001);
  for (double azimuth : {0.0, 100.0, 200.0}) {
    const std::vector<float> cube = SunAndSky(8, azimuth);
    const double e = Compare(RelightWith(b, cube, 384), DenseFromRows(b, cube)).rel_rms;
    std::printf("azimuth %5.0f  all lights rel_rms %.5f\n", azimuth, e);
    EXPECT_LT(e, 0.01);
  }
  const std::vector<float> white(3 * 384, 1.0f);
  EXPECT_LT(Compare(RelightWith(b, white, 384), DenseFromRows(b, white)).rel_rms, 0.01);
}

}  // namespace
}  // namespace wavebake
