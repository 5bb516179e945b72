// Near-field area lights on real plane-domain stores (--light-domain plane:S):
// the bake's record of the domain, the wavelet path against the analytic
// form factor of a rectangle, against its own brute force, against the
// Monte-Carlo reference; lights behind the plane, several lights, textures.
// In tests/driver because the driver links both the bake and the runtime.
#include "runtime/near_field/near_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>

#include "driver/bake/embedded_bake.h"
#include "driver/relight/area_relight.h"
#include "runtime/near_field/near_field_brute.h"
#include "runtime/reference/area_reference.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/json_file.h"
#include "tests/testing/scratch_dir.h"

namespace wavebake::driver {
namespace {

using TempDir = test_support::ScratchDir;

// builtin:furnace (a flat ground of albedo 1 at y = 0, nothing else) over
// plane:4, N = 16, kept nearly losslessly so the tests see the method, not
// the column compression.
class NearFieldStoreTest : public ::testing::Test {
 protected:
  // A failed bake fails every test (an ASSERT here would only skip them).
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>("near_field");
    BakeParams p;
    p.light_res = 16;
    p.layout = "camera:32x32";
    p.tile_size = 16;
    p.column_group = 128;
    p.target_error = 0.002;
    p.light_domain = *ParseLightDomain("plane:4");
    path_ = dir_->path() / "furnace_plane.wbk";
    absl::StatusOr<v1::Job> job = driver::EmbeddedBake("builtin:furnace", p, path_, {.workers = 2});
    if (!job.ok() || job->phase() != v1::PHASE_DONE) {
      setup_error_ = job.ok() ? job->error() : job.status().ToString();
      return;
    }
    absl::StatusOr<NearFieldStore> s = OpenNearFieldStore(path_);
    if (!s.ok()) setup_error_ = s.status().ToString();
    if (s.ok()) store_ = std::make_unique<NearFieldStore>(*std::move(s));
  }
  static void TearDownTestSuite() {
    store_.reset();
    dir_.reset();
  }
  void SetUp() override { ASSERT_EQ(setup_error_, "") << "the suite's bake failed"; }

  static std::vector<float> Relight(const std::vector<AreaLight>& lights, double source = 1,
                                    double target = 1, int threads = 2) {
    std::vector<float> rgb(3 * store_->samples.cells());
    absl::StatusOr<NearFieldStats> s =
        RelightNearField(*store_, lights, {source, target, nullptr, threads}, rgb);
    EXPECT_TRUE(s.ok()) << s.status();
    return rgb;
  }

  static inline std::unique_ptr<TempDir> dir_;
  static inline std::filesystem::path path_;
  static inline std::unique_ptr<NearFieldStore> store_;
  static inline std::string setup_error_;
};

AreaLight Square(double cx, double cz, double height, double size, Vec3 radiance) {
  AreaLight l;
  l.centre = {cx, cz};
  l.height = height;
  l.size = {size, size};
  l.radiance = radiance;
  l.resolution = 16;
  return l;
}

// The form factor from a point with normal +Y to the rectangle [x0,x1]×[z0,z1]
// (relative to the point) at height h above it, facing down: superposition
// of the corner formula (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + (X ↔ Y)].
double FormFactor(double x0, double x1, double z0, double z1, double h) {
  const auto corner = [h](double x, double z) {
    const double X = x / h, Y = z / h, a = std::sqrt(1 + X * X), b = std::sqrt(1 + Y * Y);
    return (X / a * std::atan(Y / a) + Y / b * std::atan(X / b)) / (2 * std::numbers::pi);
  };
  return corner(x1, z1) - corner(x0, z1) - corner(x1, z0) + corner(x0, z0);
}

TEST_F(NearFieldStoreTest, TheStoreRecordsItsPlaneDomain) {
  absl::StatusOr<nlohmann::json> attrs = ReadJsonFile(path_ / ".zattrs");
  ASSERT_TRUE(attrs.ok());
  EXPECT_EQ((*attrs)["params"]["light_domain"], "plane:4");
  EXPECT_EQ((*attrs)["M"], 16 * 16);
  EXPECT_EQ(store_->rows.columns(), 256);
  EXPECT_EQ(store_->face.size(), 4);
  // An environment cannot light it; an area light cannot light a cube store.
  absl::StatusOr<OpenedStore> opened = OpenStore(path_);
  ASSERT_TRUE(opened.ok());
  absl::StatusOr<EnvMap> env = LoadEnvMap("builtin:constant");
  ASSERT_TRUE(env.ok());
  EXPECT_EQ(RelightImage(*opened, *env, 8).status().code(), absl::StatusCode::kFailedPrecondition);
}

// A constant square above an unoccluded ground: B = albedo · L · F, F the
// analytic form factor. The face (S = 4) holds the whole light for every
// sample here, so what is left is the face's discretization.
TEST_F(NearFieldStoreTest, ConstantSquareMatchesTheAnalyticFormFactor) {
  const AreaLight light = Square(0.2, -0.3, 1.5, 1.0, {2, 2, 2});
  const std::vector<float> rgb = Relight({light});
  const SampleSet& s = store_->samples;
  double err = 0, norm = 0;
  int checked = 0;
  for (int cell = 0; cell < s.cells(); ++cell) {
    const int32_t id = s.grid[cell];
    if (id < 0) continue;
    const Vec3 p = s.position[id];
    const double f =
        FormFactor(light.centre[0] - 0.5 - p.x, light.centre[0] + 0.5 - p.x,
                   light.centre[1] - 0.5 - p.z, light.centre[1] + 0.5 - p.z, light.height - p.y);
    const double expected = s.albedo[id][0] * 2 * f;
    err += (rgb[3 * cell] - expected) * (rgb[3 * cell] - expected);
    norm += expected * expected;
    ++checked;
  }
  ASSERT_GT(checked, 500);
  EXPECT_LT(std::sqrt(err / norm), 0.03);
}

// Every source and target kept, the wavelet path computes exactly what
// resampling the light onto each face in pixels and a dense product do.
TEST_F(NearFieldStoreTest, AllTermsEqualTheBruteForce) {
  AreaLight light = Square(-0.4, 0.1, 0.9, 1.3, {1, 0.5, 0.25});
  light.rotation_degrees = 30;
  const std::vector<float> wavelet = Relight({light});
  BruteForceNearField brute(*store_);
  std::vector<float> pixels(wavelet.size());
  const std::vector<LightCanvas> canvases = {DrawLight(light)};
  brute.Relight(canvases, 2, pixels);
  double peak = 0;
  for (size_t i = 0; i < pixels.size(); ++i)
    if (!std::isnan(pixels[i])) peak = std::max(peak, double(pixels[i]));
  ASSERT_GT(peak, 0.05);
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (std::isnan(pixels[i])) {
      EXPECT_TRUE(std::isnan(wavelet[i]));
      continue;
    }
    ASSERT_NEAR(wavelet[i], pixels[i], 1e-4 * peak) << i;
  }
}

// A frame does not depend on how many threads share it (each cell is
// computed by the same code whichever thread takes it).
TEST_F(NearFieldStoreTest, BitIdenticalForAnyThreadCount) {
  AreaLight light = Square(0.3, -0.2, 0.7, 1.5, {1, 0.8, 0.6});
  light.texture = EnvMap{2, 2, {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}};
  light.rotation_degrees = 15;
  const std::vector<float> one = Relight({light}, 0.02, 0.3, 1),
                           three = Relight({light}, 0.02, 0.3, 3);
  ASSERT_EQ(one.size(), three.size());
  EXPECT_EQ(0, std::memcmp(one.data(), three.data(), one.size() * sizeof(float)));
}

// §5.2: only points in front of the light receive it. The ground is at
// y = 0: a light at or below it lights nothing, and adding one changes
// nothing; lights add.
TEST_F(NearFieldStoreTest, BehindThePlaneNothingAndLightsAdd) {
  for (double h : {0.0, -0.5}) {
    const std::vector<float> rgb = Relight({Square(0, 0, h, 1, {1, 1, 1})});
    for (float v : rgb) {
      if (!std::isnan(v)) {
        ASSERT_EQ(v, 0.0f) << "height " << h;
      }
    }
  }
  const AreaLight a = Square(-0.5, 0, 1.0, 0.6, {1, 0.2, 0.2});
  const AreaLight b = Square(0.7, -0.4, 1.8, 0.9, {0.1, 0.3, 1});
  const AreaLight behind = Square(0, 0, -0.2, 3, {5, 5, 5});
  const std::vector<float> ab = Relight({a, b, behind}, 0.05, 0.3);
  const std::vector<float> only_a = Relight({a}, 0.05, 0.3), only_b = Relight({b}, 0.05, 0.3);
  double peak = 0;
  for (size_t i = 0; i < ab.size(); ++i) {
    if (std::isnan(ab[i])) continue;
    peak = std::max(peak, double(ab[i]));
    ASSERT_NEAR(ab[i], only_a[i] + only_b[i], 1e-6 + 1e-5 * ab[i]);
  }
  EXPECT_GT(peak, 0.01);
}

// A texture of two pixels (u < ½ red, u ≥ ½ blue) is the two half lights
// side by side; rotated 90°, the halves swap axes the same way. This pins
// the texture's orientation in the wavelet path and in the reference alike.
TEST_F(NearFieldStoreTest, ATextureIsTheSumOfItsPixels) {
  AreaLight textured = Square(0.1, 0.2, 1.2, 1.0, {1, 1, 1});
  textured.size = {1.0, 0.5};
  textured.texture = EnvMap{2, 1, {1, 0, 0, 0, 0, 1}};
  for (double rotation : {0.0, 90.0}) {
    textured.rotation_degrees = rotation;
    const double c = std::cos(rotation * std::numbers::pi / 180),
                 s = std::sin(rotation * std::numbers::pi / 180);
    AreaLight red = textured, blue = textured;
    red.texture = blue.texture = EnvMap{};
    red.size = blue.size = {0.5, 0.5};
    red.radiance = {1, 0, 0};
    blue.radiance = {0, 0, 1};
    red.centre = {0.1 - 0.25 * c, 0.2 - 0.25 * s};
    blue.centre = {0.1 + 0.25 * c, 0.2 + 0.25 * s};
    const std::vector<float> whole = Relight({textured}), halves = Relight({red, blue});
    for (size_t i = 0; i < whole.size(); ++i) {
      if (!std::isnan(whole[i])) {
        ASSERT_NEAR(whole[i], halves[i], 2e-3) << "rotation " << rotation;
      }
    }

    absl::StatusOr<RayCaster> caster = BuildBakedScene(store_->info);
    ASSERT_TRUE(caster.ok());
    AreaReferenceOptions o{.strata = 8, .batches = 4, .threads = 2};
    auto ref_whole = ComputeAreaReference(*caster, store_->samples, {&textured, 1}, o);
    std::vector<AreaLight> pair = {red, blue};
    auto ref_halves = ComputeAreaReference(*caster, store_->samples, pair, o);
    ASSERT_TRUE(ref_whole.ok() && ref_halves.ok());
    EXPECT_LT(CompareToReference(ref_whole->rgb, ref_halves->rgb).rel_rms, 0.03);
  }
}

// The independent reference meets the analytic form factor too, and the
// wavelet path with the paper's truncation (1 % / 30 %) stays close to it.
TEST_F(NearFieldStoreTest, ReferenceAndTruncatedPathAgreeWithTheFormFactor) {
  const AreaLight light = Square(-0.3, 0.4, 1.1, 0.8, {3, 3, 3});
  absl::StatusOr<RayCaster> caster = BuildBakedScene(store_->info);
  ASSERT_TRUE(caster.ok());
  auto ref = ComputeAreaReference(*caster, store_->samples, {&light, 1},
                                  {.strata = 8, .batches = 4, .threads = 2});
  ASSERT_TRUE(ref.ok()) << ref.status();
  const SampleSet& s = store_->samples;
  std::vector<float> analytic(3 * s.cells(), std::nanf(""));
  for (int cell = 0; cell < s.cells(); ++cell) {
    const int32_t id = s.grid[cell];
    if (id < 0) continue;
    const Vec3 p = s.position[id];
    const double f = FormFactor(-0.7 - p.x, 0.1 - p.x, 0.0 - p.z, 0.8 - p.z, 1.1 - p.y);
    for (int c = 0; c < 3; ++c) analytic[3 * cell + c] = float(3 * f * s.albedo[id][c]);
  }
  EXPECT_LT(CompareToReference(ref->rgb, analytic).rel_rms, 0.01);
  EXPECT_LT(ref->rel_se, 0.01);
  EXPECT_LT(CompareToReference(Relight({light}, 0.01, 0.3), analytic).rel_rms, 0.05);
  // Grazing loss (§5.4.3): it falls with S, and an S = 10 face misses less
  // than 2 % of this light.
  for (size_t j = 1; j < ref->grazing_loss.size(); ++j)
    EXPECT_LE(ref->grazing_loss[j], ref->grazing_loss[j - 1]);
  EXPECT_LT(ref->grazing_loss.back(), 0.02);
}

// A rotated, textured light: the wavelet path (every term kept) and the
// reference agree, which pins the rotation's sense and the texture's
// orientation across the two (the halves test above checks each alone).
TEST_F(NearFieldStoreTest, RotatedTextureAgreesWithTheReference) {
  AreaLight light = Square(0.2, 0.1, 1.0, 1.2, {2, 2, 2});
  light.size = {1.4, 0.7};
  light.rotation_degrees = 35;
  light.texture = EnvMap{2, 2, {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0}};
  absl::StatusOr<RayCaster> caster = BuildBakedScene(store_->info);
  ASSERT_TRUE(caster.ok());
  auto ref = ComputeAreaReference(*caster, store_->samples, {&light, 1},
                                  {.strata = 8, .batches = 4, .threads = 2});
  ASSERT_TRUE(ref.ok()) << ref.status();
  EXPECT_LT(CompareToReference(Relight({light}), ref->rgb).rel_rms, 0.03);
  AreaLight mirrored = light;  // the other sense of rotation is far off
  mirrored.rotation_degrees = -35;
  EXPECT_GT(CompareToReference(Relight({mirrored}), ref->rgb).rel_rms, 0.1);
}

TEST_F(NearFieldStoreTest, SequenceWritesEveryFrameAndItsTime) {
  const std::filesystem::path seq = dir_->path() / "seq.json";
  std::ofstream(seq) << R"({"frames": 3,
      "from": {"centre": [0, 0], "height": 1, "size": [0.5, 0.5], "radiance": [1, 1, 1]},
      "to": {"centre": [0.5, 0], "size": [1, 1]}})";
  const std::filesystem::path out = dir_->path() / "frames";
  absl::StatusOr<AreaSequenceSummary> sum = RelightAreaSequence(path_, seq, {}, {}, out, ".exr");
  ASSERT_TRUE(sum.ok()) << sum.status();
  EXPECT_EQ(sum->frames, 3);
  for (const char* f : {"frame_0000.exr", "frame_0001.exr", "frame_0002.exr", "timing.csv"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  std::ifstream csv(out / "timing.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 4);
}

}  // namespace
}  // namespace wavebake::driver
