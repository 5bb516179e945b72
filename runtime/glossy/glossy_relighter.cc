#include "runtime/glossy/glossy_relighter.h"

#include <algorithm>
#include <cstdlib>
#include <thread>

#include "absl/strings/str_cat.h"
#include "core/util/check_or_die.h"
#include "core/util/parallel_for.h"
#include "runtime/relight/relighter.h"

namespace wavebake {
namespace {

absl::Status CheckSlices(const BrdfSlices& s, const SampleRows& rows) {
  if (s.light_res != rows.light_res() || s.first.size() != static_cast<size_t>(rows.cells()) + 1)
    return absl::InvalidArgumentError(
        absl::StrCat("brdf slices: made for N = ", s.light_res, " and ", s.first.size() - 1,
                     " cells, the rows have N = ", rows.light_res(), " and ", rows.cells()));
  return absl::OkStatus();
}

constexpr int kBlock = 64;  // cells per work item: neighbours share cache lines of L's tree

}  // namespace

HaarFactor LightingFactor(const WaveletLights& lights) {
  std::vector<float> dense(static_cast<size_t>(18) * lights.light_res * lights.light_res, 0.0f);
  for (const WaveletLight& l : lights.lights) {
    for (int c = 0; c < 3; ++c) dense[3 * static_cast<size_t>(l.column) + c] += l.weight[c];
  }
  return HaarFactor::FromDense(lights.light_res, dense);
}

absl::StatusOr<GlossyRelighter> GlossyRelighter::Create(const SampleRows* rows,
                                                        const SampleSet& samples, BrdfSlices slices,
                                                        int threads) {
  if (rows == nullptr) return absl::InvalidArgumentError("rows: null");
  if (samples.width != rows->width() || samples.height != rows->height())
    return absl::InvalidArgumentError(absl::StrCat("samples: grid ", samples.width, "x",
                                                   samples.height, " but the rows have ",
                                                   rows->width(), "x", rows->height()));
  if (absl::Status s = CheckSlices(slices, *rows); !s.ok()) return s;
  GlossyRelighter r;
  r.rows_ = rows;
  r.slices_ = std::move(slices);
  r.albedo_ = CellAlbedo(samples);
  r.masked_.resize(rows->cells());
  for (int c = 0; c < rows->cells(); ++c) r.masked_[c] = samples.grid[c] < 0;
  r.threads_ = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  r.threads_ = std::max(r.threads_, 1);
  for (int t = 0; t < r.threads_; ++t)
    r.scratch_.push_back(std::make_unique<Scratch>(rows->light_res()));
  r.GatherSlices();
  return r;
}

absl::Status GlossyRelighter::SetSlices(BrdfSlices slices) {
  if (absl::Status s = CheckSlices(slices, *rows_); !s.ok()) return s;
  slices_ = std::move(slices);
  GatherSlices();
  return absl::OkStatus();
}

namespace {

// ρ_x's terms face by face: indices increase, so each face's are one range.
struct FaceRanges {
  std::array<uint32_t, 7> start{};
  std::array<bool, 6> faces{};
  FaceRanges(std::span<const uint32_t> gi, uint32_t per_face) {
    for (uint32_t face = 0; face < 6; ++face) {
      start[face + 1] = static_cast<uint32_t>(
          std::lower_bound(gi.begin() + start[face], gi.end(), (face + 1) * per_face) - gi.begin());
      faces[face] = start[face + 1] > start[face];
    }
  }
  size_t size(int face) const { return start[face + 1] - start[face]; }
};

}  // namespace

void GlossyRelighter::GatherSlices() {
  gathered_.assign(rows_->entries(), HaarProduct::Gathered{});
  const uint32_t per_face = static_cast<uint32_t>(light_res()) * light_res();
  ParallelForWorkers(cells(), threads_, kBlock, [&](int worker, int cell) {
    if (masked_[cell]) return;
    const std::span<const uint32_t> gi = slices_.Index(cell);
    const std::span<const float> gv = slices_.Value(cell);
    const FaceRanges r(gi, per_face);
    for (int face = 0; face < 6; ++face) {
      const std::span<const uint32_t> terms = rows_->terms(cell, face);
      if (!r.faces[face] || terms.empty()) continue;
      scratch_[worker]->product.Gather(
          face, gi.subspan(r.start[face], r.size(face)), gv.subspan(r.start[face], r.size(face)),
          terms, std::span(gathered_).subspan(rows_->EntryOf(cell, face), terms.size()));
    }
  });
}

void GlossyRelighter::Transport(const HaarFactor& lighting, const BrdfSlices& slices,
                                std::span<float> rgb_out) {
  CheckOrDie("GlossyRelighter", lighting.n() == light_res(),
             "lighting made for another light resolution");
  CheckOrDie("GlossyRelighter", slices.first.size() == static_cast<size_t>(cells()) + 1,
             "slices of another grid");
  CheckOrDie("GlossyRelighter", rgb_out.size() == 3 * static_cast<size_t>(cells()),
             "output is not W*H*3 floats");
  const bool own = &slices == &slices_;
  const uint32_t per_face = static_cast<uint32_t>(light_res()) * light_res();
  ParallelForWorkers(cells(), threads_, kBlock, [&](int worker, int cell) {
    float* out = rgb_out.data() + 3 * static_cast<size_t>(cell);
    out[0] = out[1] = out[2] = 0;
    if (masked_[cell]) return;
    Scratch& s = *scratch_[worker];
    const std::span<const uint32_t> gi = slices.Index(cell);
    const std::span<const float> gv = slices.Value(cell);
    const FaceRanges r(gi, per_face);
    const std::array<float, 3> b = rows_->Apply(
        cell, r.faces,
        [&](int face, std::span<const uint32_t> terms, int64_t entry, std::span<float> rgb) {
          const auto g_index = gi.subspan(r.start[face], r.size(face));
          const auto g_value = gv.subspan(r.start[face], r.size(face));
          if (own) {
            s.product.Combine(lighting, face, g_index, g_value, terms,
                              std::span(gathered_).subspan(entry, terms.size()), rgb);
          } else {
            s.product.AtTerms(lighting, face, g_index, g_value, terms, rgb);
          }
        },
        s.weights);
    for (int c = 0; c < 3; ++c) out[c] = b[c];
  });
}

void GlossyRelighter::ApplyAlbedo(std::span<const float> transport_rgb,
                                  std::span<float> rgb_out) const {
  CheckOrDie("GlossyRelighter",
             transport_rgb.size() == albedo_.size() && rgb_out.size() == albedo_.size(),
             "ApplyAlbedo: buffers are not W*H*3 floats");
  for (size_t i = 0; i < albedo_.size(); ++i) rgb_out[i] = transport_rgb[i] * albedo_[i];
}

void GlossyRelighter::Relight(const WaveletLights& lights, std::span<float> rgb_out) {
  CheckOrDie("GlossyRelighter", lights.light_res == light_res(),
             "lights were made for another light resolution");
  Transport(LightingFactor(lights), slices_, rgb_out);
  ApplyAlbedo(rgb_out, rgb_out);
}

}  // namespace wavebake
