// The near-field charts of docs/RESULTS.md (bench/charts.sh runs it):
//
//   build/bench_charts_near OUT_DIR [--quick] [--threads T]
//
// Stores: builtin:cubes-wall, camera:64x64, plane:4, N = 32, target 1 %
// (quick: 32x32, N = 16), baked once into OUT_DIR/work. Errors are eval's
// relative RMS against the Monte-Carlo reference over the light's area
// (runtime/reference/area_reference.h), traced for every light.
//
// Chart 9, near_height.csv: error against the light's height (size 1.0) and
// against its size (height 1.2), for this method (1 % source, 30 % target
// terms) and for the same light treated as distant (its image at the scene
// centre lighting every sample, the paper's Fig. 8c); with the reference's
// grazing loss at S = 4, the part of the light a plane:4 face cannot see.
//
// Chart 10, near_terms.csv (the paper's Figs. 10 and 11): error and
// single-thread frame time against the source fraction (target 100 % and
// 30 %) and the target fraction (source 1 % and 100 %), for two textures:
// the softbox of docs/lights (four flat panels) and an 8×8 checker of the
// same colours (finer detail, more source terms needed). Beside the error
// against the reference, the error against the untruncated method (100 %
// / 100 %), which is the truncation alone.
//
// near_grazing.csv: the energy an expanded face of size S misses (§5.4.3),
// from the reference, for lights at three heights; and the paper's Fig. 7e
// curves for an unoccluded cosine lobe (the face's share of the hemisphere's
// solid angle and of the lobe's energy).
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "bench/chart_util.h"
#include "driver/bake/embedded_bake.h"
#include "runtime/near_field/near_field.h"
#include "runtime/reference/area_eval.h"
#include "runtime/reference/area_reference.h"
#include "runtime/reference/eval.h"

namespace wavebake {
namespace {

using charts::Csv;
using charts::Die;
using charts::Value;

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

struct Setup {
  bool quick = false;
  int threads = 2;
  std::filesystem::path out;
};

std::filesystem::path BakeOnce(const Setup& s, const std::string& scene, const std::string& name,
                               const std::string& layout) {
  const std::filesystem::path p = s.out / "work" / name;
  if (std::filesystem::exists(p / ".zattrs")) return p;
  std::filesystem::create_directories(p.parent_path());
  BakeParams params;
  params.light_res = s.quick ? 16 : 32;
  params.layout = layout;
  params.light_domain = *ParseLightDomain("plane:4");
  std::fprintf(stderr, "baking %s ...\n", p.c_str());
  v1::Job job = Value(driver::EmbeddedBake(scene, params, p, {.workers = s.threads}));
  if (job.phase() != v1::PHASE_DONE) Die("bake failed: " + job.error());
  return p;
}

EnvMap Checker(int cells) {
  const float c[4][3] = {
      {1, 0.84f, 0.58f}, {1, 0.4f, 0.05f}, {0.1f, 0.58f, 0.64f}, {0.58f, 0.3f, 1}};
  EnvMap t{32, 32, std::vector<float>(32 * 32 * 3)};
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const int k = ((x * cells / 32) + 2 * (y * cells / 32)) % 4;
      for (int ch = 0; ch < 3; ++ch) t.rgb[(y * 32 + x) * 3 + ch] = c[k][ch];
    }
  return t;
}

EnvMap Softbox() {  // docs/lights/softbox.png, linear
  return Checker(2);
}

AreaLight Light(double height, double size, const EnvMap& texture) {
  AreaLight l;
  l.centre = {0.3, 0.8};  // docs/lights/softbox.json
  l.height = height;
  l.size = {size * 1.4, size};
  l.radiance = {3, 3, 3};
  l.texture = texture;
  l.resolution = 32;
  return l;
}

AreaReferenceResult Reference(const Setup& s, const RayCaster& caster, const NearFieldStore& st,
                              const AreaLight& light) {
  AreaReferenceOptions o;
  o.axis = st.face.axis();
  o.batches = s.quick ? 4 : 8;
  o.threads = s.threads;
  o.epsilon = BakedEpsilon(st.info, caster);
  o.face_sizes = {2, 3, 4, 5, 6, 7, 8, 9, 10};
  return Value(ComputeAreaReference(caster, st.samples, {&light, 1}, o));
}

std::vector<float> Near(const NearFieldStore& st, const AreaLight& light, double src, double tgt,
                        int threads, double* seconds = nullptr) {
  std::vector<float> rgb(3 * st.samples.cells());
  const double t0 = ThreadSeconds();
  Value(RelightNearField(st, {&light, 1}, {src, tgt, nullptr, threads}, rgb));
  if (seconds) *seconds = ThreadSeconds() - t0;
  return rgb;
}

void HeightChart(const Setup& s, const RayCaster& caster, const NearFieldStore& st) {
  Csv csv(s.out / "near_height.csv",
          "sweep,height,size,near_rel_rms,distant_rel_rms,near_facing_rel_rms,"
          "distant_facing_rel_rms,reference_rel_se,grazing_loss_s4");
  const EnvMap tex = Softbox();
  const std::vector<double> heights =
      s.quick ? std::vector<double>{0.6, 1.2, 3}
              : std::vector<double>{0.6, 0.8, 1.0, 1.2, 1.6, 2.0, 3.0, 4.0};
  const std::vector<double> sizes =
      s.quick ? std::vector<double>{0.5, 2} : std::vector<double>{0.3, 0.5, 1.0, 1.5, 2.0, 3.0};
  const auto row = [&](const char* sweep, double h, double size) {
    const AreaLight light = Light(h, size, tex);
    const AreaReferenceResult ref = Reference(s, caster, st, light);
    const std::vector<float> facing = FacingOnly(st.samples, st.face.frame(), ref.rgb);
    const std::vector<float> rgb = Near(st, light, 0.01, 0.3, s.threads);
    const double near = CompareToReference(rgb, ref.rgb).rel_rms;
    std::vector<float> distant(3 * st.samples.cells());
    RelightDistant(st, {&light, 1}, SampleCentre(st.samples), distant);
    const double far = CompareToReference(distant, ref.rgb).rel_rms;
    csv.Row(sweep, h, size, near, far, CompareToReference(rgb, facing).rel_rms,
            CompareToReference(distant, facing).rel_rms, ref.rel_se, ref.grazing_loss[2]);
    std::fprintf(stderr, "chart 9: %s h %.2f size %.2f: near %.4f distant %.4f loss %.4f\n", sweep,
                 h, size, near, far, ref.grazing_loss[2]);
  };
  for (double h : heights) row("height", h, 1.0);
  for (double size : sizes) row("size", 1.2, size);
}

void TermsChart(const Setup& s, const RayCaster& caster, const NearFieldStore& st) {
  Csv csv(s.out / "near_terms.csv",
          "texture,sweep,source_fraction,target_fraction,rel_rms_reference,rel_rms_untruncated,"
          "ms_per_frame,targets_per_sample,sources");
  const std::vector<double> fractions =
      s.quick ? std::vector<double>{0.01, 0.3, 1}
              : std::vector<double>{0.0025, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 1};
  for (const auto& [name, tex] : {std::pair{"softbox", Softbox()}, {"checker8", Checker(8)}}) {
    const AreaLight light = Light(1.2, 1.0, tex);
    const AreaReferenceResult ref = Reference(s, caster, st, light);
    const std::vector<float> full = Near(st, light, 1, 1, s.threads);
    const auto row = [&](const char* sweep, double src, double tgt) {
      double best = 1e30;
      std::vector<float> rgb;
      for (int rep = 0; rep < (s.quick ? 1 : 3); ++rep) {  // fastest of 3: the least disturbed
        double sec = 0;
        rgb = Near(st, light, src, tgt, 1, &sec);
        best = std::min(best, sec);
      }
      std::vector<float> scratch(rgb.size());
      const NearFieldStats stats =
          Value(RelightNearField(st, {&light, 1}, {src, tgt, nullptr, s.threads}, scratch));
      csv.Row(name, sweep, src, tgt, CompareToReference(rgb, ref.rgb).rel_rms,
              CompareToReference(rgb, full).rel_rms, 1e3 * best,
              double(stats.targets) / std::max<int64_t>(1, stats.lit_samples), stats.sources);
    };
    for (double tgt : {1.0, 0.3})
      for (double f : fractions) row("source", f, tgt);
    for (double src : {0.01, 1.0})
      for (double f : fractions) row("target", src, f);
    std::fprintf(stderr, "chart 10: %s done\n", name);
  }
}

void GrazingChart(const Setup& s, const RayCaster& caster, const NearFieldStore& st) {
  Csv csv(s.out / "near_grazing.csv", "curve,height,face_size,value");
  const EnvMap tex = Softbox();
  for (double h : {0.6, 1.2, 2.4}) {
    const AreaReferenceResult ref = Reference(s, caster, st, Light(h, 1.0, tex));
    const std::vector<double> sizes = {2, 3, 4, 5, 6, 7, 8, 9, 10};
    for (size_t j = 0; j < sizes.size(); ++j) csv.Row("loss", h, sizes[j], ref.grazing_loss[j]);
  }
  // Fig. 7e: solid angle of the face over 2π, and its share of ∫ cos/π.
  for (double size = 2; size <= 10.001; size += 0.5) {
    const PlaneFace face(64, size, kPosY);
    double lobe = 0;
    for (int m = 0; m < face.texels(); ++m)
      lobe += face.SolidAngle(m) * Dot(face.TexelCenter(m), {0, 1, 0}) / std::numbers::pi;
    csv.Row("hemisphere_coverage", 0, size, face.TotalSolidAngle() / (2 * std::numbers::pi));
    csv.Row("cosine_lobe_coverage", 0, size, lobe);
  }
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  using namespace wavebake;
  charts::program = "bench_charts_near";
  Setup s;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick")) {
      s.quick = true;
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      s.threads = std::atoi(argv[++i]);
    } else {
      s.out = argv[i];
    }
  }
  if (s.out.empty()) Die("usage: bench_charts_near OUT_DIR [--quick] [--threads T]");
  std::filesystem::create_directories(s.out);
  const auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path path = BakeOnce(s, "builtin:cubes-wall", "cubes_plane4.wbk",
                                              s.quick ? "camera:32x32" : "camera:64x64");
  const NearFieldStore st = Value(OpenNearFieldStore(path));
  const RayCaster caster = Value(BuildBakedScene(st.info));
  HeightChart(s, caster, st);
  TermsChart(s, caster, st);
  GrazingChart(s, caster, st);
  std::fprintf(stderr, "charts: %s (%.0f s)\n", s.out.c_str(), charts::SecondsSince(t0));
  return 0;
}
