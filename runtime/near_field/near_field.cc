#include "runtime/near_field/near_field.h"

#include <atomic>
#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/products/target_selection.h"
#include "core/util/parallel_for.h"
#include "runtime/relight/relighter.h"

namespace wavebake {
namespace {

// Cells per task: round-robin tasks of a few hundred samples balance the
// threads (the paper's §5.3.2 uses 512 vertices).
constexpr int kChunk = 512;

struct LightFrame {
  LightCanvas canvas;
  std::vector<SourceTerm> sources;
};

}  // namespace

FaceView ViewFrom(const PlaneFace& face, const LightCanvas& canvas, Vec3 p) {
  FaceView v;
  const FaceFrame& f = face.frame();
  const double z = canvas.height - Dot(p, f.major);
  if (!(z > 0)) return v;  // on or behind the light plane: it does not see the front
  v.map = canvas.MapAt(Dot(p, f.s_axis), Dot(p, f.t_axis), z, face.size());
  // The canvas [0,1]² pulled back through q = s v + o, clipped to the face.
  v.ax = std::max(0.0, -v.map.o_x / v.map.s_x);
  v.bx = std::min(1.0, (1 - v.map.o_x) / v.map.s_x);
  v.ay = std::max(0.0, -v.map.o_y / v.map.s_y);
  v.by = std::min(1.0, (1 - v.map.o_y) / v.map.s_y);
  v.lit = v.bx > v.ax && v.by > v.ay;
  return v;
}

void MultiplyAlbedo(const SampleSet& samples, std::span<float> rgb) {
  const std::vector<float> albedo = CellAlbedo(samples);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] *= albedo[i];
}

absl::StatusOr<NearFieldStore> OpenNearFieldStore(const std::filesystem::path& path) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(path);
  if (!info.ok()) return info.status();
  const LightDomain& d = info->params.light_domain;
  if (!d.is_plane())
    return absl::FailedPreconditionError(
        absl::StrCat("store: ", path.string(),
                     " was baked over the cube; an area light needs a store baked "
                     "with --light-domain plane:S (relight this one with --env)"));
  absl::StatusOr<SampleSet> samples = ReadSamples(path);
  if (!samples.ok()) return samples.status();
  absl::StatusOr<CompressedColumns> columns = ReadTransport(path);
  if (!columns.ok()) return columns.status();
  if (columns->row_filter != WaveletFilter::kHaar)
    return absl::FailedPreconditionError(
        "store: affine coupling needs Haar rows (baked with --row-filter daub4)");
  absl::StatusOr<CellRows> rows = CellRows::Decode(*columns, *samples);
  if (!rows.ok()) return rows.status();
  const PlaneFace face(info->light_res, d);
  return NearFieldStore{*std::move(info), *std::move(samples), face, *std::move(rows)};
}

absl::StatusOr<NearFieldStats> RelightNearField(const NearFieldStore& store,
                                                std::span<const AreaLight> lights,
                                                const NearFieldOptions& o,
                                                std::span<float> rgb_out) {
  if (!(o.source_fraction > 0 && o.source_fraction <= 1))
    return absl::InvalidArgumentError(
        absl::StrCat("source_fraction: ", o.source_fraction, " is outside (0, 1]"));
  if (!(o.target_fraction > 0 && o.target_fraction <= 1))
    return absl::InvalidArgumentError(
        absl::StrCat("target_fraction: ", o.target_fraction, " is outside (0, 1]"));
  const int n = store.face.n();
  for (const AreaLight& l : lights) {
    if (o.table &&
        (o.table->options().source_res != l.resolution || o.table->options().target_res != n))
      return absl::InvalidArgumentError(absl::StrCat(
          "coupling table: made for ", o.table->options().source_res, " -> ",
          o.table->options().target_res, ", the light needs ", l.resolution, " -> ", n));
  }
  const auto t0 = std::chrono::steady_clock::now();
  NearFieldStats stats;
  stats.lights = static_cast<int>(lights.size());
  std::vector<LightFrame> frames;
  for (const AreaLight& l : lights) {
    LightFrame f{DrawLight(l), {}};
    f.sources = SelectSources(f.canvas, o.source_fraction);
    stats.sources += static_cast<int64_t>(f.sources.size());
    frames.push_back(std::move(f));
  }
  const int budget = std::max(1, static_cast<int>(std::lround(o.target_fraction * n * n)));
  const SampleSet& samples = store.samples;
  std::atomic<int64_t> lit{0}, targets_total{0};
  struct State {
    std::vector<AffinePropagator> propagators;
    TargetSelector selector;
    std::vector<uint16_t> targets;
    std::vector<float> rgb;
  };
  ParallelChunks(
      samples.cells(), kChunk, o.threads,
      [&] {
        State s{{}, TargetSelector(n), {}, std::vector<float>(3 * n * n)};
        for (const LightFrame& f : frames)
          s.propagators.emplace_back(f.sources, f.canvas.res, n, o.table);
        return s;
      },
      [&](State& s, int begin, int end) {
        int64_t my_lit = 0, my_targets = 0;
        for (int cell = begin; cell < end; ++cell) {
          std::array<float, 3> sum{};
          const int32_t id = samples.grid[cell];
          for (size_t li = 0; id >= 0 && li < frames.size(); ++li) {
            const FaceView v = ViewFrom(store.face, frames[li].canvas, samples.position[id]);
            if (!v.lit) continue;
            s.selector.Select(v.ax, v.bx, v.ay, v.by, budget, s.targets);
            s.propagators[li].Propagate(v.map, s.targets, s.rgb);
            const std::array<float, 3> b = store.rows.Dot(cell, s.targets, s.rgb);
            for (int c = 0; c < 3; ++c) sum[c] += b[c];
            ++my_lit;
            my_targets += static_cast<int64_t>(s.targets.size());
          }
          for (int c = 0; c < 3; ++c) rgb_out[3 * size_t(cell) + c] = sum[c];
        }
        lit += my_lit;
        targets_total += my_targets;
      });
  MultiplyAlbedo(samples, rgb_out);
  stats.lit_samples = lit;
  stats.targets = targets_total;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

std::vector<float> FaceCoefficients(const PlaneFace& face, const LightCanvas& canvas,
                                    Vec3 position) {
  const int n = face.n(), r = canvas.res;
  std::vector<float> rgb(3 * size_t(n) * n, 0.0f);
  const FaceView v = ViewFrom(face, canvas, position);
  if (!v.lit) return rgb;
  std::vector<SourceTerm> all;
  for (int m = 0; m < r * r; ++m) {
    const size_t t = size_t(r) * r;
    all.push_back({static_cast<uint16_t>(m % r),
                   static_cast<uint16_t>(m / r),
                   {canvas.coeffs[m], canvas.coeffs[t + m], canvas.coeffs[2 * t + m]}});
  }
  std::vector<uint16_t> targets(n * n);
  for (int k = 0; k < n * n; ++k) targets[k] = static_cast<uint16_t>(k);
  AffinePropagator(all, r, n).Propagate(v.map, targets, rgb);
  return rgb;
}

Vec3 SampleCentre(const SampleSet& samples) {
  double sum[3] = {0, 0, 0};
  for (const Vec3& p : samples.position) sum[0] += p.x, sum[1] += p.y, sum[2] += p.z;
  const double n = std::max<size_t>(1, samples.position.size());
  return {float(sum[0] / n), float(sum[1] / n), float(sum[2] / n)};
}

void RelightDistant(const NearFieldStore& store, std::span<const AreaLight> lights, Vec3 centre,
                    std::span<float> rgb_out) {
  const int m = store.face.texels();
  std::vector<float> env(3 * size_t(m), 0.0f);
  for (const AreaLight& l : lights) {
    const std::vector<float> c = FaceCoefficients(store.face, DrawLight(l), centre);
    for (size_t i = 0; i < env.size(); ++i) env[i] += c[i];
  }
  std::vector<uint16_t> all(m);
  for (int k = 0; k < m; ++k) all[k] = static_cast<uint16_t>(k);
  for (int cell = 0; cell < store.samples.cells(); ++cell) {
    const std::array<float, 3> b = store.rows.Dot(cell, all, env);
    for (int c = 0; c < 3; ++c) rgb_out[3 * size_t(cell) + c] = b[c];
  }
  MultiplyAlbedo(store.samples, rgb_out);
}

}  // namespace wavebake
