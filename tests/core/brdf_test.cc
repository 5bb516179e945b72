// White-furnace energy tests of the BRDF library against numerical
// integration (midpoint rule on a polar grid around each lobe's axis):
// directional albedo ∫ f_r cos θ_i dω_i is 1 where the normalization makes
// it exact (Lambert always; Phong and Blinn–Phong at normal incidence) and
// never above 1; GGX's D integrates to 1 over projected microfacet area and
// passes Heitz's weak white furnace. The samplers' densities integrate to 1
// and importance sampling reproduces the numerical albedo.
#include "core/products/brdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include "core/products/ggx.h"

namespace wavebake {
namespace {

const Vec3 kNormal = Normalize(Vec3{0.2f, 0.9f, -0.3f});

// ∫_{S²} f(ω) dω, polar grid around `axis`.
template <typename F>
double IntegrateSphere(Vec3 axis, const F& f, int n_theta = 2000, int n_phi = 360) {
  Vec3 t, b;
  OrthonormalFrame(axis, t, b);
  const double dt = std::numbers::pi / n_theta, dp = 2 * std::numbers::pi / n_phi;
  double sum = 0;
  for (int i = 0; i < n_theta; ++i) {
    const double theta = (i + 0.5) * dt, st = std::sin(theta), ct = std::cos(theta);
    double ring = 0;
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * dp;
      const Vec3 w = t * static_cast<float>(st * std::cos(phi)) +
                     b * static_cast<float>(st * std::sin(phi)) + axis * static_cast<float>(ct);
      ring += f(Normalize(w));
    }
    sum += ring * st;
  }
  return sum * dt * dp;
}

// The view at polar angle `theta` from the normal.
Vec3 ViewAt(double theta) {
  Vec3 t, b;
  OrthonormalFrame(kNormal, t, b);
  return Normalize(kNormal * static_cast<float>(std::cos(theta)) +
                   t * static_cast<float>(std::sin(theta)));
}

std::unique_ptr<Brdf> MakeBrdf(const std::string& spec) {
  absl::StatusOr<std::unique_ptr<Brdf>> b = ParseBrdf(spec);
  EXPECT_TRUE(b.ok()) << b.status();
  return *std::move(b);
}

double Albedo(const Brdf& brdf, Vec3 wo) {
  // Integrate around the lobe's axis so narrow lobes get enough samples.
  const LobeCone cone = brdf.Support(kNormal, wo, 1e-3);
  return IntegrateSphere(cone.axis, [&](Vec3 wi) {
    return brdf.Eval(kNormal, wo, wi) * std::max(0.0f, Dot(kNormal, wi));
  });
}

TEST(BrdfFurnace, LambertReflectsEverythingFromEveryDirection) {
  const auto brdf = MakeBrdf("lambert");
  for (double theta : {0.0, 0.7, 1.4}) EXPECT_NEAR(Albedo(*brdf, ViewAt(theta)), 1.0, 1e-4);
}

TEST(BrdfFurnace, NormalizedPhongAndBlinnAreExactAtNormalIncidence) {
  for (const char* spec :
       {"phong:1", "phong:8", "phong:32", "phong:128", "blinn:8", "blinn:32", "blinn:128"}) {
    const auto brdf = MakeBrdf(spec);
    EXPECT_NEAR(Albedo(*brdf, kNormal), 1.0, 2e-3) << spec;
  }
}

TEST(BrdfFurnace, NoBrdfReflectsMoreThanItReceives) {
  for (const char* spec : {"phong:8", "phong:128", "blinn:32", "ggx:0.05", "ggx:0.3", "ggx:1"}) {
    const auto brdf = MakeBrdf(spec);
    for (double theta : {0.3, 0.9, 1.3}) {
      const double a = Albedo(*brdf, ViewAt(theta));
      EXPECT_LE(a, 1.0 + 2e-3) << spec << " at " << theta;
      EXPECT_GT(a, 0.05) << spec << " at " << theta;
    }
  }
}

TEST(GgxFurnace, DistributionCoversTheProjectedArea) {
  for (double alpha : {0.05, 0.2, 0.6, 1.0}) {
    const double area = IntegrateSphere(
        kNormal,
        [&](Vec3 h) { return ggx::D(alpha, Dot(kNormal, h)) * std::max(0.0f, Dot(kNormal, h)); },
        4000, 8);  // D is symmetric about n: few azimuths suffice
    EXPECT_NEAR(area, 1.0, 1e-3) << alpha;
  }
}

// Heitz 2014 §3: ∫ D(h) G₁(ω_o) / (4 cos θ_o) dω_i = 1 over the sphere.
TEST(GgxFurnace, WeakWhiteFurnace) {
  for (double alpha : {0.05, 0.3, 1.0}) {
    for (double theta : {0.2, 0.8, 1.3}) {
      const Vec3 wo = ViewAt(theta);
      const double co = Dot(kNormal, wo);
      const double v = IntegrateSphere(
          Reflect(wo, kNormal),
          [&](Vec3 wi) {
            const Vec3 h = Normalize(wi + wo);
            return ggx::D(alpha, Dot(kNormal, h)) * ggx::G1(alpha, co) / (4 * co);
          },
          3000, 360);
      EXPECT_NEAR(v, 1.0, 3e-3) << alpha << " at " << theta;
    }
  }
}

TEST(BrdfSampling, DensitiesIntegrateToOne) {
  for (const char* spec : {"lambert", "phong:32", "blinn:32", "ggx:0.2"}) {
    const auto brdf = MakeBrdf(spec);
    for (double theta : {0.0, 1.0}) {
      const Vec3 wo = ViewAt(theta);
      const LobeCone cone = brdf->Support(kNormal, wo, 1e-3);
      const double total =
          IntegrateSphere(cone.axis, [&](Vec3 wi) { return brdf->Pdf(kNormal, wo, wi); });
      EXPECT_NEAR(total, 1.0, 2e-3) << spec << " at " << theta;
    }
  }
}

TEST(BrdfSampling, ImportanceSamplingReproducesTheAlbedo) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (const char* spec : {"lambert", "phong:8", "phong:128", "blinn:32", "ggx:0.1", "ggx:0.7"}) {
    const auto brdf = MakeBrdf(spec);
    const Vec3 wo = ViewAt(0.8);
    double sum = 0, sum_sq = 0;
    const int count = 40000;
    for (int i = 0; i < count; ++i) {
      const Vec3 wi = brdf->Sample(kNormal, wo, u(rng), u(rng));
      const double pdf = brdf->Pdf(kNormal, wo, wi);
      const double x =
          pdf > 0 ? brdf->Eval(kNormal, wo, wi) * std::max(0.0f, Dot(kNormal, wi)) / pdf : 0;
      sum += x;
      sum_sq += x * x;
    }
    const double mean = sum / count;
    const double se = std::sqrt(std::max(0.0, sum_sq / count - mean * mean) / count);
    EXPECT_NEAR(mean, Albedo(*brdf, wo), 5 * se + 1e-3) << spec;
  }
}

// The projection's fast path sums the same thing Eval does.
TEST(Brdf, SumOverDirectionsIsTheSumOfEvalTimesCosine) {
  std::mt19937 rng(11);
  std::normal_distribution<float> g(0, 1);
  std::vector<float> x, y, z;
  for (int i = 0; i < 500; ++i) {
    const Vec3 w = Normalize(Vec3{g(rng), g(rng), g(rng)});
    x.push_back(w.x), y.push_back(w.y), z.push_back(w.z);
  }
  for (const char* spec : {"lambert", "phong:32", "phong:7.5", "blinn:16", "ggx:0.4"}) {
    const auto brdf = MakeBrdf(spec);
    const Vec3 wo = ViewAt(0.6);
    double want = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      const Vec3 w{x[i], y[i], z[i]};
      want += brdf->Eval(kNormal, wo, w) * std::max(0.0f, Dot(kNormal, w));
    }
    EXPECT_NEAR(brdf->SumOverDirections(kNormal, wo, x.data(), y.data(), z.data(), 500), want,
                1e-5 * want)
        << spec;
  }
}

TEST(Brdf, IsReciprocal) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (const char* spec : {"phong:20", "blinn:20", "ggx:0.3"}) {
    const auto brdf = MakeBrdf(spec);
    for (int i = 0; i < 200; ++i) {
      const Vec3 a = ViewAt(1.5 * u(rng)), b = brdf->Sample(kNormal, a, u(rng), u(rng));
      EXPECT_NEAR(brdf->Eval(kNormal, a, b), brdf->Eval(kNormal, b, a),
                  1e-4 * (1 + brdf->Eval(kNormal, a, b)))
          << spec;
    }
  }
}

TEST(Brdf, ParseNamesTheFieldAndRoundTrips) {
  for (const char* bad : {"", "phong", "phong:", "phong:-1", "ggx:2", "ward:0.1", "blinn:nan"}) {
    absl::StatusOr<std::unique_ptr<Brdf>> b = ParseBrdf(bad);
    ASSERT_FALSE(b.ok()) << bad;
    EXPECT_NE(b.status().message().find("brdf"), std::string::npos);
  }
  for (const char* good : {"lambert", "phong:32", "blinn:8", "ggx:0.25"}) {
    EXPECT_EQ(MakeBrdf(good)->Name(), good);
  }
  EXPECT_FALSE(MakeBrdf("lambert")->ViewDependent());
  EXPECT_TRUE(MakeBrdf("phong:32")->ViewDependent());
}

}  // namespace
}  // namespace wavebake
