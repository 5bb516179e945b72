#include "core/transport/bounce_gather.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "core/util/parallel_for.h"

namespace wavebake {
namespace {

// splitmix64 (Steele et al. 2014): the gather's own stream per sample.
uint64_t GatherMix(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

uint64_t StreamSeed(uint64_t seed, uint64_t stream) {
  const uint64_t salted = GatherMix(seed ^ 0x6761746865725F62ull);
  return stream == 0 ? salted : GatherMix(salted ^ stream);
}

class GatherRng {
 public:
  // The salt keeps these streams apart from any other use of the job seed.
  // Stream 0 (a layout's gather from its own samples) is the job seed's
  // stream as such; another stream is mixed in first.
  GatherRng(uint64_t seed, uint64_t stream, uint64_t sample)
      : state_(GatherMix(StreamSeed(seed, stream) ^ sample)) {}
  double Uniform() {  // [0, 1)
    state_ = GatherMix(state_);
    return static_cast<double>(state_ >> 11) * 0x1.0p-53;
  }

 private:
  uint64_t state_;
};

// An orthonormal frame around unit n (Duff et al. 2017, branchless).
void GatherFrame(Vec3 n, Vec3& t, Vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

// Cosine-distributed direction from a point of the unit square: Shirley's
// concentric map to the disk, lifted to the hemisphere (Malley's method),
// which keeps the strata of the square compact on the hemisphere.
Vec3 CosineDirection(double u, double v, Vec3 n, Vec3 t, Vec3 b) {
  const double a = 2 * u - 1, c = 2 * v - 1;
  double r = 0, phi = 0;
  if (a != 0 || c != 0) {
    if (std::abs(a) > std::abs(c)) {
      r = a;
      phi = (std::numbers::pi / 4) * (c / a);
    } else {
      r = c;
      phi = (std::numbers::pi / 2) - (std::numbers::pi / 4) * (a / c);
    }
  }
  const double dx = r * std::cos(phi), dy = r * std::sin(phi);
  const double dz = std::sqrt(std::max(0.0, 1 - dx * dx - dy * dy));
  return Normalize(t * static_cast<float>(dx) + b * static_cast<float>(dy) +
                   n * static_cast<float>(dz));
}

// Barycentric coordinates of p in triangle (a, b, c), clamped to the
// triangle and summing to 1 (p is Embree's hit point, on the triangle up to
// rounding).
std::array<double, 3> HitBarycentric(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = Dot(e0, e0), d01 = Dot(e0, e1), d11 = Dot(e1, e1);
  const double d20 = Dot(d, e0), d21 = Dot(d, e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0);
  double u = 1 - v - w;
  if (u < 0) {
    v /= v + w;
    w = 1 - v;
    u = 0;
  }
  return {u, v, w};
}

}  // namespace

void BounceGather::Apply(std::span<const float> in, std::span<float> out) const {
  for (int c = 0; c < cells; ++c) {
    float sum = 0;
    for (int64_t e = offsets[c]; e < offsets[c + 1]; ++e) sum += weight[e] * in[source[e]];
    out[c] = sum;
  }
}

namespace {

// The rows of G times an interleaved block of n vectors (BounceGather::
// ApplyBlock). N > 0 fixes n at compile time, so the n sums stay in
// registers; N = 0 takes n at run time. Inlined into the two clones below.
template <int N>
inline __attribute__((always_inline)) void ApplyRows(const BounceGather& g,
                                                     std::span<const uint8_t> live,
                                                     std::span<const float> in,
                                                     std::span<float> out, int n) {
  if constexpr (N > 0) n = N;
  float acc[BounceGather::kMaxBlock];
  for (int c = 0; c < g.cells; ++c) {
    std::fill_n(acc, n, 0.0f);
    for (int64_t e = g.offsets[c]; e < g.offsets[c + 1]; ++e) {
      const int32_t j = g.source[e];
      if (!live[j]) continue;
      const float w = g.weight[e];
      const float* src = in.data() + size_t(j) * n;
      for (int k = 0; k < n; ++k) acc[k] += w * src[k];
    }
    std::copy_n(acc, n, out.data() + size_t(c) * n);
  }
}

// The AVX2 clones have no FMA (not in the avx2 target), so they multiply and
// add as the default clones do: the same bits on every machine, 8 floats at
// a time instead of 4. Float sums: a row has at most 3R entries of weight
// ≤ 1/R, so rounding stays near 1e-6 of the value, far below the gather's
// own 1/√R noise, at twice the throughput of double sums. (Clang clones no
// templates, hence two functions.)
__attribute__((target_clones("avx2", "default"))) void ApplyFullBlock(const BounceGather& g,
                                                                      std::span<const uint8_t> live,
                                                                      std::span<const float> in,
                                                                      std::span<float> out) {
  ApplyRows<BounceGather::kMaxBlock>(g, live, in, out, BounceGather::kMaxBlock);
}
__attribute__((target_clones("avx2", "default"))) void ApplyPartialBlock(
    const BounceGather& g, std::span<const uint8_t> live, std::span<const float> in,
    std::span<float> out, int n) {
  ApplyRows<0>(g, live, in, out, n);
}

}  // namespace

void BounceGather::ApplyBlock(std::span<const float> in, std::span<float> out, int n) const {
  // A source whose n values are all zero adds exactly +0 to each sum (the
  // sums start at +0 and round to nearest, so none is ever −0), so its
  // entries are skipped, to the bit. Haar-domain column images are mostly
  // zero: on cubes-wall's auxiliary set (camera 128², N = 32) 70 % of the
  // values and 51 % of the sources of a 32-column block are.
  std::vector<uint8_t> live(sources);
  for (int j = 0; j < sources; ++j) {
    const float* src = in.data() + size_t(j) * n;
    live[j] = std::any_of(src, src + n, [](float v) { return v != 0; });
  }
  if (n == kMaxBlock)
    ApplyFullBlock(*this, live, in, out);
  else
    ApplyPartialBlock(*this, live, in, out, n);
}

namespace {

// Where the previous bounce is read at a hit point: the sample cells around
// it and their interpolation weights (summing to 1 over covered cells).
class HitInterpolant {
 public:
  virtual ~HitInterpolant() = default;
  // Appends (cell, weight·w_k) pairs for the hit (mesh, triangle, β).
  virtual void Add(uint32_t mesh, uint32_t triangle, const std::array<double, 3>& beta,
                   double weight, std::vector<std::pair<int32_t, double>>& row) const = 0;
};

// Vertex layouts: barycentric over the triangle's vertex samples.
class VertexInterpolant : public HitInterpolant {
 public:
  VertexInterpolant(const Scene& scene, std::vector<int32_t> cell_of_vertex)
      : scene_(scene), cell_of_vertex_(std::move(cell_of_vertex)) {
    uint32_t first = 0;
    for (const Mesh& m : scene.meshes) {
      first_vertex_.push_back(first);
      first += static_cast<uint32_t>(m.positions.size());
    }
  }
  void Add(uint32_t mesh, uint32_t triangle, const std::array<double, 3>& beta, double weight,
           std::vector<std::pair<int32_t, double>>& row) const override {
    const std::array<uint32_t, 3>& tri = scene_.meshes[mesh].triangles[triangle];
    for (int k = 0; k < 3; ++k) {
      const int32_t src = cell_of_vertex_[first_vertex_[mesh] + tri[k]];
      if (src >= 0 && beta[k] > 0) row.emplace_back(src, weight * beta[k]);
    }
  }

 private:
  const Scene& scene_;
  std::vector<int32_t> cell_of_vertex_;
  std::vector<uint32_t> first_vertex_;
};

// uv layouts: the hit's texture coordinate in the mesh's chart
// (core/layouts/uv_atlas.h convention: texel (x, y) centred at x + 1/2, row 0 at v1),
// bilinear over the four nearest texel centres of the chart that a sample
// covers, renormalized over them (a hit next to the chart's border or an
// uncovered texel reads its covered neighbours).
class UvInterpolant : public HitInterpolant {
 public:
  UvInterpolant(const Scene& scene, const SampleSet& samples, int channel)
      : scene_(scene), samples_(samples), channel_(channel) {}
  void Add(uint32_t mesh, uint32_t triangle, const std::array<double, 3>& beta, double weight,
           std::vector<std::pair<int32_t, double>>& row) const override {
    const Mesh& m = scene_.meshes[mesh];
    const UvChart& c = samples_.uv_charts[mesh];
    const std::array<uint32_t, 3>& tri = m.triangles[triangle];
    double u = 0, v = 0;
    for (int k = 0; k < 3; ++k) {
      u += beta[k] * m.uv_channels[channel_][tri[k]].u;
      v += beta[k] * m.uv_channels[channel_][tri[k]].v;
    }
    const double fx = c.x + (u - c.u0) * c.width / (double(c.u1) - c.u0) - 0.5;
    const double fy = c.y + (c.v1 - v) * c.height / (double(c.v1) - c.v0) - 0.5;
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const double tx = fx - x0, ty = fy - y0;
    std::array<std::pair<int32_t, double>, 4> taps;
    int n = 0;
    double total = 0;
    for (int dy = 0; dy <= 1; ++dy) {
      for (int dx = 0; dx <= 1; ++dx) {
        const int x = x0 + dx, y = y0 + dy;
        if (x < c.x || y < c.y || x >= c.x + c.width || y >= c.y + c.height) continue;
        const int32_t cell = y * samples_.width + x;
        if (samples_.grid[cell] < 0) continue;
        const double w = (dx ? tx : 1 - tx) * (dy ? ty : 1 - ty);
        if (!(w > 0)) continue;
        taps[n++] = {cell, w};
        total += w;
      }
    }
    for (int k = 0; k < n; ++k) row.emplace_back(taps[k].first, weight * taps[k].second / total);
  }

 private:
  const Scene& scene_;
  const SampleSet& samples_;
  int channel_;
};

}  // namespace

absl::StatusOr<BounceGather> MakeBounceGather(const Scene& scene, const RayCaster& caster,
                                              const SampleSet& samples,
                                              const BounceGatherOptions& options) {
  return MakeBounceGather(scene, caster, samples, samples, options);
}

absl::StatusOr<BounceGather> MakeBounceGather(const Scene& scene, const RayCaster& caster,
                                              const SampleSet& receivers, const SampleSet& samples,
                                              const BounceGatherOptions& options) {
  if (options.rays < 1 || options.rays > 65536)
    return absl::InvalidArgumentError(
        absl::StrCat("gather_rays: ", options.rays, " is outside 1..65536"));
  std::unique_ptr<HitInterpolant> interpolant;
  if (options.uv_channel >= 0) {
    if (samples.uv_charts.size() != scene.meshes.size())
      return absl::InvalidArgumentError("bounces: the uv layout's charts do not match the meshes");
    for (const Mesh& m : scene.meshes)
      if (static_cast<size_t>(options.uv_channel) >= m.uv_channels.size())
        return absl::InvalidArgumentError(
            absl::StrCat("bounces: mesh '", m.name, "' has no UV channel ", options.uv_channel));
    interpolant = std::make_unique<UvInterpolant>(scene, samples, options.uv_channel);
  } else {
    if (samples.vertex.empty() || samples.vertex.size() != samples.position.size())
      return absl::InvalidArgumentError(
          "bounces: the layout's samples are not mesh vertices or lightmap texels, so a ray's hit "
          "point has no samples to interpolate the previous bounce from (bounces need a "
          "hilbert, grid or uv layout)");
    // Global vertex id → cell (−1: not a sample).
    uint32_t vertices = 0;
    for (const Mesh& m : scene.meshes) vertices += static_cast<uint32_t>(m.positions.size());
    std::vector<int32_t> cell_of_vertex(vertices, -1);
    for (int c = 0; c < samples.cells(); ++c) {
      const int32_t s = samples.grid[c];
      if (s < 0) continue;
      const int32_t v = samples.vertex[s];
      if (v < 0 || static_cast<uint32_t>(v) >= vertices)
        return absl::InvalidArgumentError(
            absl::StrCat("bounces: sample ", s, " names vertex ", v, " outside the scene"));
      cell_of_vertex[v] = c;
    }
    interpolant = std::make_unique<VertexInterpolant>(scene, std::move(cell_of_vertex));
  }
  std::vector<float> mean_albedo;
  for (const Mesh& m : scene.meshes)
    mean_albedo.push_back((m.albedo.x + m.albedo.y + m.albedo.z) / 3.0f);

  int q = 1;
  while (q * q < options.rays) ++q;
  const int rays = q * q;
  const float epsilon = options.epsilon > 0 ? options.epsilon : caster.DefaultEpsilon();

  // Each cell's entries, built independently (any thread count, same bytes).
  std::vector<std::vector<std::pair<int32_t, double>>> rows(receivers.cells());
  std::vector<uint64_t> hits(receivers.cells(), 0);
  ParallelForWorkers(receivers.cells(), options.threads, 16, [&](int, int c) {
    const int32_t s = receivers.grid[c];
    if (s < 0) return;
    const Vec3 n = receivers.normal[s];
    Vec3 t, b;
    GatherFrame(n, t, b);
    const Vec3 origin = receivers.position[s] + n * epsilon;
    GatherRng rng(options.seed, options.stream, static_cast<uint64_t>(s));
    std::vector<std::pair<int32_t, double>>& row = rows[c];
    for (int i = 0; i < q; ++i) {
      for (int j = 0; j < q; ++j) {
        const double u = (i + rng.Uniform()) / q, v = (j + rng.Uniform()) / q;
        const Vec3 dir = CosineDirection(u, v, n, t, b);
        const std::optional<Hit> hit = caster.FirstHit(origin, dir);
        if (!hit || !(Dot(hit->normal, dir) < 0)) continue;  // escaped, or a back face
        ++hits[c];
        const Mesh& mesh = scene.meshes[hit->mesh];
        const std::array<uint32_t, 3>& tri = mesh.triangles[hit->triangle];
        const std::array<double, 3> beta = HitBarycentric(
            hit->position, mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
        interpolant->Add(hit->mesh, hit->triangle, beta, double(mean_albedo[hit->mesh]) / rays,
                         row);
      }
    }
    // Sources ascending and merged; stable, so equal sources add in ray order.
    std::stable_sort(row.begin(), row.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    size_t out = 0;
    for (size_t k = 0; k < row.size(); ++k) {
      if (out > 0 && row[out - 1].first == row[k].first) {
        row[out - 1].second += row[k].second;
      } else {
        row[out++] = row[k];
      }
    }
    row.resize(out);
  });

  BounceGather g;
  g.cells = receivers.cells();
  g.sources = samples.cells();
  g.rays = rays;
  g.offsets.assign(size_t(g.cells) + 1, 0);
  for (int c = 0; c < g.cells; ++c) {
    g.offsets[c + 1] = g.offsets[c] + static_cast<int64_t>(rows[c].size());
    g.hits += hits[c];
  }
  g.source.reserve(g.offsets.back());
  g.weight.reserve(g.offsets.back());
  for (std::vector<std::pair<int32_t, double>>& row : rows) {
    for (const auto& [src, w] : row) {
      g.source.push_back(src);
      g.weight.push_back(static_cast<float>(w));
    }
    std::vector<std::pair<int32_t, double>>().swap(row);
  }
  return g;
}

AutoBounceChoice AutoBounces(const BounceGather& gather, std::span<const int32_t> grid,
                             double target_error, int max_bounces) {
  std::vector<float> v(gather.cells, 0.0f), next(gather.cells, 0.0f);
  double norm0 = 0;
  for (int c = 0; c < gather.cells; ++c) {
    if (grid[c] < 0) continue;
    v[c] = 1;
    norm0 += 1;
  }
  norm0 = std::sqrt(norm0);
  AutoBounceChoice choice;
  choice.estimate.push_back(1.0);
  for (int b = 0; b < max_bounces; ++b) {
    gather.Apply(v, next);
    double norm = 0;
    for (float x : next) norm += double(x) * x;
    const double e = norm0 > 0 ? std::sqrt(norm) / norm0 : 0.0;
    choice.estimate.push_back(e);
    if (e <= target_error / 2) return choice;  // bounce b+1 is not needed
    choice.bounces = b + 1;
    v.swap(next);
  }
  return choice;
}

}  // namespace wavebake
