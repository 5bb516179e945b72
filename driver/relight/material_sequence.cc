#include "driver/relight/material_sequence.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "driver/relight/relight_sequence.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"
#include "storage/files/atomic_file.h"

namespace wavebake::driver {
namespace {

absl::Status BadMaterialSequence(std::string_view spec, std::string_view why) {
  return absl::InvalidArgumentError(absl::StrCat("brdf-sequence: '", std::string(spec), "' ",
                                                 std::string(why),
                                                 " (KIND:FROM:TO:FRAMES[:HOLD], KIND phong, "
                                                 "blinn or ggx)"));
}

// Eq. 4.4–4.5 per cell: Δ = the n largest entries of target − approx, and
// approx += Δ. Both slices sorted by index; the difference is their merge.
BrdfSlices DeltaAndUpdate(const BrdfSlices& target, BrdfSlices& approx, int n) {
  BrdfSlices delta, next;
  delta.light_res = next.light_res = target.light_res;
  const int cells = static_cast<int>(target.first.size()) - 1;
  delta.first.assign(cells + 1, 0);
  next.first.assign(cells + 1, 0);
  std::vector<uint32_t> diff_index, d_index;
  std::vector<float> diff_value, d_value;
  for (int c = 0; c < cells; ++c) {
    const auto ti = target.Index(c), ai = approx.Index(c);
    const auto tv = target.Value(c), av = approx.Value(c);
    diff_index.clear(), diff_value.clear();
    for (size_t i = 0, j = 0; i < ti.size() || j < ai.size();) {
      const bool take_t = j == ai.size() || (i < ti.size() && ti[i] <= ai[j]);
      const bool take_a = i == ti.size() || (j < ai.size() && ai[j] <= ti[i]);
      const uint32_t m = take_t ? ti[i] : ai[j];
      const float d = (take_t ? tv[i] : 0.0f) - (take_a ? av[j] : 0.0f);
      i += take_t, j += take_a;
      if (d != 0) diff_index.push_back(m), diff_value.push_back(d);
    }
    d_index.clear(), d_value.clear();
    KeepLargest(diff_index, diff_value, n, d_index, d_value);
    delta.index.insert(delta.index.end(), d_index.begin(), d_index.end());
    delta.value.insert(delta.value.end(), d_value.begin(), d_value.end());
    delta.first[c + 1] = static_cast<int64_t>(delta.index.size());
    // approx + Δ, again a merge; entries that become 0 are dropped.
    for (size_t i = 0, j = 0; i < ai.size() || j < d_index.size();) {
      const bool take_a = j == d_index.size() || (i < ai.size() && ai[i] <= d_index[j]);
      const bool take_d = i == ai.size() || (j < d_index.size() && d_index[j] <= ai[i]);
      const uint32_t m = take_a ? ai[i] : d_index[j];
      const float v = (take_a ? av[i] : 0.0f) + (take_d ? d_value[j] : 0.0f);
      i += take_a, j += take_d;
      if (v != 0) next.index.push_back(m), next.value.push_back(v);
    }
    next.first[c + 1] = static_cast<int64_t>(next.index.size());
  }
  approx = std::move(next);
  return delta;
}

}  // namespace

std::string BrdfSequence::At(int i) const {
  const double t = frames > 1 ? std::min(1.0, double(i) / (frames - 1)) : 1.0;
  const double v = kind == "ggx" ? from + (to - from) * t : from * std::pow(to / from, t);
  return absl::StrCat(kind, ":", i >= frames - 1 ? to : v);
}

absl::StatusOr<BrdfSequence> ParseBrdfSequence(std::string_view spec) {
  const std::vector<std::string> parts = absl::StrSplit(std::string(spec), ':');
  if (parts.size() != 4 && parts.size() != 5)
    return BadMaterialSequence(spec, "needs 4 or 5 fields");
  BrdfSequence s{.kind = parts[0]};
  if (s.kind != "phong" && s.kind != "blinn" && s.kind != "ggx")
    return BadMaterialSequence(spec, "has no editable parameter in its KIND");
  if (!absl::SimpleAtod(parts[1], &s.from) || !absl::SimpleAtod(parts[2], &s.to))
    return BadMaterialSequence(spec, "has a FROM or TO that is not a number");
  if (!absl::SimpleAtoi(parts[3], &s.frames) || s.frames < 1 || s.frames > 10000)
    return BadMaterialSequence(spec, "needs FRAMES in 1..10000");
  if (parts.size() == 5 && (!absl::SimpleAtoi(parts[4], &s.hold) || s.hold < 0 || s.hold > 10000))
    return BadMaterialSequence(spec, "needs HOLD in 0..10000");
  for (const std::string& b : {s.At(0), s.At(s.total() - 1)}) {
    if (absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(b); !brdf.ok())
      return BadMaterialSequence(spec, std::string(brdf.status().message()));
  }
  return s;
}

absl::StatusOr<std::vector<MaterialFrame>> RelightMaterialSequence(
    const std::filesystem::path& store, std::string_view env_spec,
    const MaterialSequenceOptions& o) {
  if (o.terms <= 0) return absl::InvalidArgumentError(absl::StrCat("terms: ", o.terms, " < 1"));
  const int budget = o.glossy.slices.terms;
  if (budget <= 0)
    return absl::InvalidArgumentError(absl::StrCat(
        "brdf-terms: ", budget, "; a material sequence needs a per-frame budget of at least 1"));
  GlossyOptions first = o.glossy;
  first.brdf = o.sequence.At(0);
  absl::StatusOr<std::unique_ptr<GlossyStore>> opened = GlossyStore::Open(store, first);
  if (!opened.ok()) return opened.status();
  GlossyStore& g = **opened;
  // The parameter moves monotonically: the sharpest lobe is at one end.
  if (absl::StatusOr<std::unique_ptr<Brdf>> last = ParseBrdf(o.sequence.At(o.sequence.total() - 1));
      !last.ok()) {
    return last.status();
  } else if (absl::Status s = CheckBrdfResolvable(**last, g.info().light_res); !s.ok()) {
    return s;
  }
  absl::StatusOr<EnvMap> env = LoadEnvMap(env_spec);
  if (!env.ok()) return env.status();
  absl::StatusOr<LightingCoefficients> lighting =
      LightingFromEnv(*env, g.info().light_res, WaveletFilter::kHaar);
  if (!lighting.ok()) return lighting.status();
  absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, o.terms);
  if (!lights.ok()) return lights.status();
  const HaarFactor factor = LightingFactor(*lights);
  if (!o.out_dir.empty()) {
    if (absl::Status s = CreateDirectories(o.out_dir); !s.ok()) return s;
  }

  GlossyRelighter& relighter = g.relighter();
  const size_t values = 3 * static_cast<size_t>(g.samples().cells());
  std::vector<float> accumulated(values, 0.0f), frame(values), delta_image(values), exact(values);
  BrdfSlices approx;  // ρ̃ per cell, starting at 0
  approx.light_res = g.info().light_res;
  approx.first.assign(g.samples().cells() + 1, 0);
  SliceOptions all = o.glossy.slices;
  all.terms = 0;
  std::vector<MaterialFrame> frames;
  for (int i = 0; i < o.sequence.total(); ++i) {
    MaterialFrame f{.index = i, .brdf = o.sequence.At(i)};
    const auto t0 = std::chrono::steady_clock::now();
    absl::StatusOr<std::unique_ptr<Brdf>> brdf = ParseBrdf(f.brdf);
    if (!brdf.ok()) return brdf.status();
    absl::StatusOr<BrdfSlices> full = g.Project(**brdf, all);
    if (!full.ok()) return full.status();
    if (o.mode == MaterialMode::kBasic) {
      const BrdfSlices delta = DeltaAndUpdate(*full, approx, budget);
      relighter.Transport(factor, delta, delta_image);
      for (size_t k = 0; k < values; ++k) accumulated[k] += delta_image[k];
      relighter.ApplyAlbedo(accumulated, frame);
    } else {
      relighter.Transport(factor, CutSlices(*full, budget), frame);
      relighter.ApplyAlbedo(frame, frame);
    }
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    relighter.Transport(factor, *full, exact);
    relighter.ApplyAlbedo(exact, exact);
    absl::StatusOr<ErrorStats> error = CompareFinite(frame, exact, absl::StrCat("frame ", i));
    if (!error.ok()) return error.status();
    f.rel_rms = error->rel_rms;
    frames.push_back(f);
    if (!o.out_dir.empty()) {
      if (absl::Status s = WriteRelit(g.info(), g.samples(), frame, o.exposure_stops,
                                      SequenceFramePath(o.out_dir, i, o.frame_extension));
          !s.ok())
        return s;
    }
  }
  if (!o.out_dir.empty()) {
    if (absl::Status s = WriteErrorsCsv(o.out_dir, "brdf", std::span<const MaterialFrame>(frames),
                                        &MaterialFrame::brdf);
        !s.ok())
      return s;
  }
  return frames;
}

}  // namespace wavebake::driver
