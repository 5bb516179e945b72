// The glossy relighter (runtime/glossy/glossy_relighter.h) end to end, on rows
// traced in-test by the bake's own kernels (tests/runtime/relight_fixtures.h)
// and kept lossless, so what is checked is the triple product itself:
//  * the decoded per-sample rows are the rows the columns came from;
//  * Lambert through the triple product is the diffuse transport (1e-3);
//  * at every term it is the dense pixel-domain product Σ L V ρ;
//  * white furnace: unoccluded, L ≡ 1, it is albedo × the BRDF's directional
//    albedo, integrated numerically from Brdf::Eval alone.
#include "runtime/glossy/glossy_relighter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/products/brdf.h"
#include "runtime/glossy/brdf_slices.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/relighter.h"
#include "runtime/relight/sample_rows.h"
#include "tests/runtime/relight_fixtures.h"

namespace wavebake {
namespace {

using testing::MiniBake;
using testing::MiniBakeOptions;

const MiniBake& Bake(const std::string& scene, Transport transport, int light_res = 8) {
  return testing::SharedBake({.scene = scene,
                              .width = 16,
                              .height = 16,
                              .light_res = light_res,
                              .target_error = 0,
                              .transport = transport});
}

std::unique_ptr<Brdf> Make(const std::string& spec) {
  absl::StatusOr<std::unique_ptr<Brdf>> b = ParseBrdf(spec);
  EXPECT_TRUE(b.ok()) << b.status();
  return *std::move(b);
}

JitterPattern Pattern(int n, int k = 4) { return *MakeJitterPattern(Cubemap(n), k, 1); }

std::vector<Vec3> Views(const SampleSet& s, Vec3 eye) {
  std::vector<Vec3> v(s.cells());
  for (int c = 0; c < s.cells(); ++c)
    if (s.grid[c] >= 0) v[c] = Normalize(eye - s.position[s.grid[c]]);
  return v;
}

// A lat-long-free lighting: random positive texel radiance, row-transformed.
LightingCoefficients RandomLighting(int n, uint32_t seed, std::vector<float>* texels) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.1f, 2.0f);
  texels->resize(18 * n * n);
  for (float& v : *texels) v = u(rng);
  return ProjectLighting(*texels, n, WaveletFilter::kHaar);
}

std::vector<float> RelightGlossy(const MiniBake& bake, const Brdf& brdf,
                                 const std::vector<Vec3>& views, const WaveletLights& lights,
                                 int brdf_terms = 0, int quadrature = 4) {
  const SampleRows rows = *SampleRows::Decode(bake.compressed);
  const BrdfSlices slices =
      *ProjectBrdfSlices(brdf, bake.samples, views, Pattern(bake.compressed.light_res, quadrature),
                         {.terms = brdf_terms, .lobe_cutoff = 0});
  GlossyRelighter g = *GlossyRelighter::Create(&rows, bake.samples, slices, 2);
  std::vector<float> out(3 * bake.samples.cells());
  g.Relight(lights, out);
  return out;
}

TEST(SampleRows, AreTheRowsTheColumnsCameFrom) {
  const MiniBake& b = Bake("builtin:sphere-plane", Transport::kVisibility);
  const absl::StatusOr<SampleRows> rows = SampleRows::Decode(b.compressed);
  ASSERT_TRUE(rows.ok()) << rows.status();
  int64_t nonzero = 0;
  for (int cell = 0; cell < rows->cells(); ++cell) {
    std::vector<float> row(b.columns, 0.0f);
    for (int face = 0; face < 6; ++face) {
      const auto terms = rows->terms(cell, face);
      const auto values = rows->values(cell, face);
      for (size_t k = 0; k < terms.size(); ++k) {
        ASSERT_EQ(terms[k] / 64, static_cast<uint32_t>(face));
        if (k > 0) {
          ASSERT_GT(terms[k], terms[k - 1]);
        }
        row[terms[k]] = values[k];
      }
    }
    for (int m = 0; m < b.columns; ++m) {
      const float want = b.wavelet_rows[static_cast<size_t>(cell) * b.columns + m];
      ASSERT_NEAR(row[m], want, 1e-5f) << cell << " " << m;
      nonzero += want != 0;
    }
  }
  EXPECT_EQ(rows->stats().nonzeros, nonzero);
}

// The two differ only by the covariance of V and cos inside a texel (the
// product of texel means against the mean of products), which shrinks like
// texel area: 1.3e-3 at N = 8, 2.8e-4 at N = 16.
TEST(GlossyRelighter, LambertIsTheDiffuseTransport) {
  const MiniBake& diffuse = Bake("builtin:sphere-plane", Transport::kDiffuse, 16);
  const MiniBake& visibility = Bake("builtin:sphere-plane", Transport::kVisibility, 16);
  std::vector<float> texels;
  const WaveletLights lights = AllWaveletLights(RandomLighting(16, 3, &texels));
  Relighter relighter = *Relighter::Create(diffuse.compressed, diffuse.samples);
  std::vector<float> want(3 * diffuse.samples.cells());
  relighter.Relight(lights, want);
  for (int quadrature : {4, 16}) {  // the bake's K, and the slices' default
    const std::vector<float> got =
        RelightGlossy(visibility, *Make("lambert"), Views(visibility.samples, {0, 2, 3.2f}), lights,
                      0, quadrature);
    EXPECT_LT(testing::Compare(got, want).rel_rms, 1e-3) << quadrature;
  }
}

TEST(GlossyRelighter, AtEveryTermIsThePixelDomainProduct) {
  const MiniBake& b = Bake("builtin:cubes-wall", Transport::kVisibility);
  const std::vector<Vec3> views = Views(b.samples, {0.4f, 2.8f, 4.4f});
  std::vector<float> texels;
  const WaveletLights lights = AllWaveletLights(RandomLighting(8, 9, &texels));
  const JitterPattern pattern = Pattern(8);
  const BrdfTexels rho(&pattern);
  for (const char* spec : {"phong:32", "blinn:16", "ggx:0.2"}) {
    const auto brdf = Make(spec);
    const std::vector<float> got = RelightGlossy(b, *brdf, views, lights);
    std::vector<float> want(got.size(), std::nanf(""));
    for (int cell = 0; cell < b.samples.cells(); ++cell) {
      const int32_t s = b.samples.grid[cell];
      if (s < 0) continue;
      std::vector<float> r(b.columns, 0.0f);
      rho.Evaluate(*brdf, b.samples.normal[s], views[cell], 0, r);
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int m = 0; m < b.columns; ++m)
          sum += double{texels[3 * m + c]} * b.pixel_rows[size_t(cell) * b.columns + m] * r[m];
        want[3 * cell + c] = static_cast<float>(sum * b.samples.albedo[s][c]);
      }
    }
    EXPECT_LT(testing::Compare(got, want).rel_rms, 1e-5) << spec;
  }
}

// The cubemap quadrature (K = 4 jittered directions per texel) is the only
// error left: 1.3 % for phong:8 at N = 8, 0.2 % at N = 16.
TEST(GlossyRelighter, WhiteFurnaceReflectsTheDirectionalAlbedo) {
  const MiniBake& b = Bake("builtin:furnace", Transport::kVisibility, 16);
  const std::vector<Vec3> views = Views(b.samples, {0, 3, 4});
  std::vector<float> ones(18 * 16 * 16, 1.0f);
  const WaveletLights lights = AllWaveletLights(ProjectLighting(ones, 16, WaveletFilter::kHaar));
  for (const char* spec : {"lambert", "phong:8", "ggx:0.5"}) {
    const auto brdf = Make(spec);
    const std::vector<float> got = RelightGlossy(b, *brdf, views, lights);
    double err = 0, norm = 0;
    for (int cell = 0; cell < b.samples.cells(); cell += 13) {
      const int32_t s = b.samples.grid[cell];
      if (s < 0) continue;
      const Vec3 n = b.samples.normal[s], wo = views[cell];
      Vec3 t, bt;
      OrthonormalFrame(n, t, bt);
      double albedo = 0;  // ∫ f cos over the hemisphere, midpoint rule
      const int nt = 300, np = 300;
      for (int i = 0; i < nt; ++i) {
        const double th = (i + 0.5) * std::numbers::pi / 2 / nt;
        for (int j = 0; j < np; ++j) {
          const double ph = (j + 0.5) * 2 * std::numbers::pi / np;
          const Vec3 w = t * float(std::sin(th) * std::cos(ph)) +
                         bt * float(std::sin(th) * std::sin(ph)) + n * float(std::cos(th));
          albedo += brdf->Eval(n, wo, Normalize(w)) * std::cos(th) * std::sin(th);
        }
      }
      albedo *= (std::numbers::pi / 2 / nt) * (2 * std::numbers::pi / np);
      for (int c = 0; c < 3; ++c) {
        const double want = albedo * b.samples.albedo[s][c];
        err += std::pow(got[3 * cell + c] - want, 2);
        norm += want * want;
      }
    }
    EXPECT_LT(std::sqrt(err / norm), 0.005) << spec;
  }
}

TEST(GlossyRelighter, BrdfTermsConvergeToEveryTerm) {
  const MiniBake& b = Bake("builtin:cubes-wall", Transport::kVisibility);
  const std::vector<Vec3> views = Views(b.samples, {0.4f, 2.8f, 4.4f});
  std::vector<float> texels;
  const WaveletLights lights = AllWaveletLights(RandomLighting(8, 4, &texels));
  const auto brdf = Make("phong:16");
  const std::vector<float> all = RelightGlossy(b, *brdf, views, lights, 0);
  double previous = 1e9;
  for (int terms : {4, 16, 64, 384}) {
    const double e = testing::Compare(RelightGlossy(b, *brdf, views, lights, terms), all).rel_rms;
    EXPECT_LE(e, previous + 1e-6) << terms;
    previous = e;
  }
  EXPECT_LT(previous, 1e-6);
}

}  // namespace
}  // namespace wavebake
