#include "runtime/relight/incremental.h"

#include <algorithm>
#include <cmath>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/columns/nla.h"
#include "core/directions/cubemap.h"
#include "runtime/relight/row_basis.h"

namespace wavebake {

absl::StatusOr<IncrementalRelighter> IncrementalRelighter::Create(Relighter* relighter, int terms,
                                                                  IncrementalPolicy policy) {
  if (relighter == nullptr) return absl::InvalidArgumentError("relighter: null");
  if (terms <= 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("terms: ", terms, " wavelet lights per frame; need at least 1"));
  }
  IncrementalRelighter r;
  r.relighter_ = relighter;
  r.terms_ = terms;
  r.policy_ = policy;
  const int n = relighter->light_res();
  const Cubemap cube(n);
  const bool basic = policy == IncrementalPolicy::kBasic;
  r.band_of_.assign(cube.size(), 0);  // kBasic: everything in band 0
  for (int m = 0; m < cube.size() && !basic; ++m) {
    const Texel t = cube.TexelOf(m);
    r.band_of_[m] = static_cast<uint8_t>(RowBand(t.x, t.y));
  }
  const int bands = basic ? 1 : std::max(RowBandCount(n), 1);
  r.support_ = SupportSolidAngles(n);
  r.approx_.assign(3 * static_cast<size_t>(cube.size()), 0.0f);
  const size_t image = 3 * static_cast<size_t>(relighter->cells());
  r.band_images_.assign(bands, std::vector<float>(image, 0.0f));
  r.stats_.assign(bands, {});
  r.importance_.resize(cube.size());
  r.band_lights_.resize(bands);
  r.delta_image_.resize(image);
  return r;
}

void IncrementalRelighter::Reset() {
  std::fill(approx_.begin(), approx_.end(), 0.0f);
  for (auto& img : band_images_) std::fill(img.begin(), img.end(), 0.0f);
}

// §6.2.2: a band is incremental when the new lighting is closer to the
// current approximation than to zero. BI (ch. 4) skips the test.
void IncrementalRelighter::DecideBands(const LightingCoefficients& lighting) {
  for (BandStats& s : stats_) s = {};
  for (size_t m = 0; m < band_of_.size(); ++m) {
    BandStats& s = stats_[band_of_[m]];
    double res = 0, full = 0;
    for (int c = 0; c < 3; ++c) {
      const double l = lighting.rgb[3 * m + c];
      res += std::fabs(l - approx_[3 * m + c]);
      full += std::fabs(l);
    }
    s.residual_l1 += support_[m] * res;
    s.lighting_l1 += support_[m] * full;
  }
  for (BandStats& s : stats_) {
    s.incremental = policy_ == IncrementalPolicy::kBasic || s.residual_l1 < s.lighting_l1;
  }
}

// Fig. 6.1 lines 3, 9–10, 14, 16: the top n of what each wavelet would
// carry, and L̃ brought up to date.
void IncrementalRelighter::ChooseLights(const LightingCoefficients& lighting) {
  for (size_t m = 0; m < band_of_.size(); ++m) {
    const bool inc = stats_[band_of_[m]].incremental;
    double sq = 0;
    for (int c = 0; c < 3; ++c) {
      const double d = lighting.rgb[3 * m + c] - (inc ? approx_[3 * m + c] : 0.0f);
      sq += d * d;
    }
    importance_[m] = static_cast<float>(std::sqrt(sq) * support_[m]);
  }
  for (auto& l : band_lights_) l.clear();
  for (size_t m = 0; m < band_of_.size(); ++m) {
    if (!stats_[band_of_[m]].incremental) {
      for (int c = 0; c < 3; ++c) approx_[3 * m + c] = 0;  // line 14
    }
  }
  for (uint32_t m : TopK(importance_, {}, terms_)) {
    if (importance_[m] == 0) break;
    WaveletLight light{m, {}};
    for (int c = 0; c < 3; ++c) {
      const float now = lighting.rgb[3 * m + c];
      light.weight[c] = now - approx_[3 * m + c];  // ΔL_j, or L_new_j after a reset
      approx_[3 * m + c] = now;
    }
    const int band = band_of_[m];
    band_lights_[band].push_back(light);
    ++stats_[band].terms;
  }
}

// Lines 11 and 17: each band's image gets T·(its lights) by Eq. 8.
void IncrementalRelighter::UpdateBandImages() {
  for (size_t b = 0; b < band_images_.size(); ++b) {
    std::vector<float>& img = band_images_[b];
    if (!stats_[b].incremental) std::fill(img.begin(), img.end(), 0.0f);
    if (band_lights_[b].empty()) continue;
    relighter_->RelightTransport(band_lights_[b], delta_image_);
    for (size_t i = 0; i < img.size(); ++i) img[i] += delta_image_[i];
  }
}

absl::Status IncrementalRelighter::Frame(const LightingCoefficients& lighting,
                                         std::span<float> rgb_out) {
  if (lighting.light_res != relighter_->light_res() || lighting.rgb.size() != approx_.size()) {
    return absl::InvalidArgumentError(absl::StrCat("lighting: light_res ", lighting.light_res,
                                                   " but the transport has ",
                                                   relighter_->light_res()));
  }
  if (rgb_out.size() != delta_image_.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("output: ", rgb_out.size(), " floats, need ", delta_image_.size()));
  }
  DecideBands(lighting);
  ChooseLights(lighting);
  UpdateBandImages();
  std::fill(rgb_out.begin(), rgb_out.end(), 0.0f);
  for (const auto& img : band_images_) {
    for (size_t i = 0; i < img.size(); ++i) rgb_out[i] += img[i];
  }
  relighter_->ApplyAlbedo(rgb_out, rgb_out);
  return absl::OkStatus();
}

}  // namespace wavebake
