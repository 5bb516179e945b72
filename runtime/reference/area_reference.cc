#include "runtime/reference/area_reference.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "core/directions/light_domain.h"
#include "core/util/parallel_for.h"
#include "runtime/reference/stream_rng.h"

namespace wavebake {
namespace {

constexpr uint64_t kDomain = 0x617265612d726566ull;  // "area-ref"

class AreaRng : public StreamRng {
 public:
  AreaRng(uint64_t seed, uint64_t stream) : StreamRng(seed, kDomain, stream) {}
};

// A light as the sampler sees it: world corner, edge vectors, normal.
struct Emitter {
  Vec3 corner, edge_u, edge_v;  // y(u, v) = corner + u·edge_u + v·edge_v
  double area;
  const AreaLight* light;
};

Emitter MakeEmitter(const AreaLight& l, const FaceFrame& f) {
  const double a = l.rotation_degrees * std::numbers::pi / 180;
  const Vec3 u_dir = f.s_axis * float(std::cos(a)) + f.t_axis * float(std::sin(a));
  const Vec3 v_dir = f.t_axis * float(std::cos(a)) - f.s_axis * float(std::sin(a));
  const Vec3 centre =
      f.s_axis * float(l.centre[0]) + f.t_axis * float(l.centre[1]) + f.major * float(l.height);
  const Vec3 eu = u_dir * float(l.size[0]), ev = v_dir * float(l.size[1]);
  return {centre - eu * 0.5f - ev * 0.5f, eu, ev, l.size[0] * l.size[1], &l};
}

// L at rectangle coordinates (u, v) ∈ [0,1)²: the texture pixel there.
Vec3 Emitted(const AreaLight& l, double u, double v) {
  if (l.texture.width == 0) return l.radiance;
  const int px = std::min(l.texture.width - 1, static_cast<int>(u * l.texture.width));
  const int py = std::min(l.texture.height - 1, static_cast<int>(v * l.texture.height));
  const float* t = &l.texture.rgb[(size_t(py) * l.texture.width + px) * 3];
  return {t[0] * l.radiance.x, t[1] * l.radiance.y, t[2] * l.radiance.z};
}

struct Accumulator {
  std::array<double, 3> sum{}, sum_sq{};  // of batch estimates
  std::vector<double> lost;               // [face size][channel]: outside that face
};

// One batch for one receiver: strata² jittered points on every light.
void Batch(const RayCaster& caster, std::span<const Emitter> lights, const FaceFrame& f, Vec3 x,
           Vec3 n, float eps, const AreaReferenceOptions& o, AreaRng& rng, Accumulator& acc,
           std::vector<float>& dx, std::vector<float>& dy, std::vector<float>& dz,
           std::vector<uint8_t>& occ, int64_t& rays) {
  const Vec3 origin = x + n * eps;
  const int k = o.strata, per = k * k;
  std::array<double, 3> batch{};
  std::vector<std::array<double, 3>> f_val(per);
  std::vector<double> need(per);
  for (const Emitter& e : lights) {
    int count = 0;
    for (int j = 0; j < k; ++j) {
      for (int i = 0; i < k; ++i) {
        const double u = (i + rng.Next01()) / k, v = (j + rng.Next01()) / k;
        const Vec3 y = e.corner + e.edge_u * float(u) + e.edge_v * float(v);
        const Vec3 d = y - origin;
        const double r2 = Dot(d, d), r = std::sqrt(r2);
        const double cos_x = Dot(n, d) / r, cos_y = Dot(f.major, d) / r;
        if (!(cos_x > 0 && cos_y > 0)) continue;  // behind the receiver or the light
        const Vec3 radiance = Emitted(*e.light, u, v);
        const double g = e.area * cos_x * cos_y / (r2 * std::numbers::pi * per);
        f_val[count] = {radiance.x * g, radiance.y * g, radiance.z * g};
        const double c = Dot(f.major, d);
        need[count] = 2 * std::max(std::fabs(Dot(f.s_axis, d)), std::fabs(Dot(f.t_axis, d))) / c;
        dx[count] = d.x, dy[count] = d.y, dz[count] = d.z;
        ++count;
      }
    }
    if (count == 0) continue;
    const size_t c = static_cast<size_t>(count);
    caster.OccludedFan(origin, {{dx.data(), c}, {dy.data(), c}, {dz.data(), c}}, 0, 1, occ);
    rays += count;
    for (int i = 0; i < count; ++i) {
      if (occ[i]) continue;
      for (int ch = 0; ch < 3; ++ch) batch[ch] += f_val[i][ch];
      for (size_t s = 0; s < o.face_sizes.size(); ++s)
        if (need[i] > o.face_sizes[s])
          for (int ch = 0; ch < 3; ++ch) acc.lost[3 * s + ch] += f_val[i][ch];
    }
  }
  for (int ch = 0; ch < 3; ++ch) {
    acc.sum[ch] += batch[ch];
    acc.sum_sq[ch] += batch[ch] * batch[ch];
  }
}

}  // namespace

absl::StatusOr<AreaReferenceResult> ComputeAreaReference(const RayCaster& caster,
                                                         const SampleSet& samples,
                                                         std::span<const AreaLight> lights,
                                                         const AreaReferenceOptions& o) {
  if (o.strata < 1 || o.strata > 64)
    return absl::InvalidArgumentError(absl::StrCat("strata: ", o.strata, " is outside 1..64"));
  if (o.batches < 2 || o.batches > 4096)
    return absl::InvalidArgumentError(absl::StrCat("batches: ", o.batches, " is outside 2..4096"));
  if (o.axis < 0 || o.axis > 5)
    return absl::InvalidArgumentError(absl::StrCat("axis: ", o.axis, " is not a cube face"));
  const auto t0 = std::chrono::steady_clock::now();
  const FaceFrame frame = FaceFrameOf(o.axis);
  std::vector<Emitter> emitters;
  for (const AreaLight& l : lights) emitters.push_back(MakeEmitter(l, frame));
  const float eps = o.epsilon > 0 ? o.epsilon : caster.DefaultEpsilon();
  const int cells = samples.cells();
  const size_t sizes = o.face_sizes.size();
  AreaReferenceResult res;
  res.rgb.assign(3 * size_t(cells), std::numeric_limits<float>::quiet_NaN());
  res.standard_error = res.rgb;
  std::vector<double> lost(size_t(cells) * sizes, 0.0);
  std::vector<int64_t> rays(cells, 0);
  struct Scratch {
    std::vector<float> dx, dy, dz;
    std::vector<uint8_t> occ;
  };
  const int per = o.strata * o.strata;
  ParallelChunks(
      cells, 64, o.threads,
      [&] {
        return Scratch{std::vector<float>(per), std::vector<float>(per), std::vector<float>(per),
                       std::vector<uint8_t>(per)};
      },
      [&](Scratch& s, int begin, int end) {
        for (int cell = begin; cell < end; ++cell) {
          const int32_t id = samples.grid[cell];
          if (id < 0) continue;
          AreaRng rng(o.seed, static_cast<uint64_t>(id));
          Accumulator acc;
          acc.lost.assign(3 * sizes, 0.0);
          for (int b = 0; b < o.batches; ++b)
            Batch(caster, emitters, frame, samples.position[id], samples.normal[id], eps, o, rng,
                  acc, s.dx, s.dy, s.dz, s.occ, rays[cell]);
          const Vec3 albedo = samples.albedo[id];
          const double nb = o.batches;
          for (int ch = 0; ch < 3; ++ch) {
            const double mean = acc.sum[ch] / nb;
            const double var = std::max(0.0, (acc.sum_sq[ch] - acc.sum[ch] * mean) / (nb - 1));
            res.rgb[3 * size_t(cell) + ch] = static_cast<float>(mean * albedo[ch]);
            res.standard_error[3 * size_t(cell) + ch] =
                static_cast<float>(std::sqrt(var / nb) * albedo[ch]);
          }
          for (size_t j = 0; j < sizes; ++j)
            for (int ch = 0; ch < 3; ++ch)
              lost[size_t(cell) * sizes + j] += acc.lost[3 * j + ch] / nb * albedo[ch];
        }
      });
  double sum_b = 0, sum_b2 = 0, sum_se2 = 0;
  std::vector<double> lost_total(sizes, 0.0);
  for (int cell = 0; cell < cells; ++cell) {
    if (samples.grid[cell] < 0) continue;
    for (int ch = 0; ch < 3; ++ch) {
      const double b = res.rgb[3 * size_t(cell) + ch],
                   se = res.standard_error[3 * size_t(cell) + ch];
      sum_b += b, sum_b2 += b * b, sum_se2 += se * se;
    }
    for (size_t j = 0; j < sizes; ++j) lost_total[j] += lost[size_t(cell) * sizes + j];
    res.rays += rays[cell];
  }
  res.rel_se = sum_b2 > 0 ? std::sqrt(sum_se2 / sum_b2) : 0;
  for (size_t j = 0; j < sizes; ++j)
    res.grazing_loss.push_back(sum_b > 0 ? lost_total[j] / sum_b : 0);
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace wavebake
