#include "core/transport_row.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>

namespace wavebake {
namespace {

// Rays per Embree call. Large enough to amortize the call and hold a whole
// texel for the largest K (256); small enough to stay in L1 on the stack,
// so a row allocates nothing.
constexpr int kBatch = 512;

struct RayBatch {
  alignas(64) float x[kBatch];
  alignas(64) float y[kBatch];
  alignas(64) float z[kBatch];
  float cosine[kBatch];   // n·ω_k > 0
  int32_t texel[kBatch];  // m of each ray
  uint8_t occluded[kBatch];
  int count = 0;
};

// The row's preconditions are programming errors, not bad input: the bake
// builds cubemap, pattern and row from one BakeParams.
void CheckOrDie(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "TransportRow: %s\n", what);
  std::abort();
}

// A texel is the conic hull of its 4 corner directions, so if none of them is
// above the horizon no direction inside it is: the texel is exactly 0 and
// needs no rays.
bool BelowHorizon(const JitterPattern& p, int m, Vec3 n) {
  const Vec3* c = &p.corners[static_cast<size_t>(m) * 4];
  return Dot(n, c[0]) <= 0 && Dot(n, c[1]) <= 0 && Dot(n, c[2]) <= 0 && Dot(n, c[3]) <= 0;
}

// Appends texel m's directions that are above the horizon; the ones below
// contribute max(0, n·ω) = 0 whatever V is, so they are not traced. Returns
// how many were below.
int AddTexel(const JitterPattern& p, int m, Vec3 n, RayBatch& b) {
  const size_t first = static_cast<size_t>(m) * p.per_texel;
  int below = 0;
  for (int k = 0; k < p.per_texel; ++k) {
    const size_t i = first + k;
    const float c = n.x * p.x[i] + n.y * p.y[i] + n.z * p.z[i];
    if (!(c > 0)) {
      ++below;
      continue;
    }
    b.x[b.count] = p.x[i];
    b.y[b.count] = p.y[i];
    b.z[b.count] = p.z[i];
    b.cosine[b.count] = c;
    b.texel[b.count] = m;
    ++b.count;
  }
  return below;
}

// Traces the batch and adds the cosines of the unoccluded rays to their
// texels (with `count_only`, 1 per unoccluded ray instead: visibility). A
// texel's rays are added in k order, so the sum is deterministic.
void Flush(const RayCaster& caster, Vec3 origin, RayBatch& b, std::span<float> row,
           TransportStats& stats, bool count_only = false) {
  if (b.count == 0) return;
  const size_t n = static_cast<size_t>(b.count);
  caster.OccludedFan(origin, {{b.x, n}, {b.y, n}, {b.z, n}}, 0,
                     std::numeric_limits<float>::infinity(), {b.occluded, n});
  for (size_t i = 0; i < n; ++i) {
    if (b.occluded[i]) {
      ++stats.rays_occluded;
    } else {
      row[b.texel[i]] += count_only ? 1.0f : b.cosine[i];
    }
  }
  stats.rays_traced += n;
  b.count = 0;
}

}  // namespace

void TransportRow(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
                  Vec3 position, Vec3 normal, float epsilon, std::span<float> row,
                  TransportStats* stats) {
  CheckOrDie(pattern.n == cubemap.n() && pattern.texels() == cubemap.size(),
             "jitter pattern was made for another cubemap");
  TransportRow(caster, pattern, position, normal, epsilon, row, stats);
}

void TransportRow(const RayCaster& caster, const JitterPattern& pattern, Vec3 position, Vec3 normal,
                  float epsilon, std::span<float> row, TransportStats* stats) {
  CheckOrDie(row.size() == static_cast<size_t>(pattern.texels()), "row size differs from M");
  CheckOrDie(pattern.per_texel <= kBatch, "supersampling exceeds the ray batch");

  TransportStats local;
  const Vec3 origin = position + normal * epsilon;  // DESIGN.md §1: rays start at x + ε n
  std::fill(row.begin(), row.end(), 0.0f);
  RayBatch batch;
  const int texels = pattern.texels();
  for (int m = 0; m < texels; ++m) {
    if (BelowHorizon(pattern, m, normal)) {
      ++local.texels_culled;
      continue;
    }
    if (batch.count + pattern.per_texel > kBatch) Flush(caster, origin, batch, row, local);
    AddTexel(pattern, m, normal, batch);
  }
  Flush(caster, origin, batch, row, local);

  // Ω_m · (1/K) · f_r with f_r = 1/π (albedo factored out, DESIGN.md §1).
  const float inv_k_pi = static_cast<float>(1.0 / (pattern.per_texel * std::numbers::pi));
  for (int m = 0; m < texels; ++m) row[m] *= pattern.solid_angle[m] * inv_k_pi;

  if (stats) {
    stats->rays_traced += local.rays_traced;
    stats->rays_occluded += local.rays_occluded;
    stats->texels_culled += local.texels_culled;
  }
}

void VisibilityRow(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
                   Vec3 position, Vec3 normal, float epsilon, std::span<float> row,
                   TransportStats* stats) {
  CheckOrDie(row.size() == static_cast<size_t>(cubemap.size()), "row size differs from M");
  CheckOrDie(pattern.n == cubemap.n() && pattern.texels() == cubemap.size(),
             "jitter pattern was made for another cubemap");
  CheckOrDie(pattern.per_texel <= kBatch, "supersampling exceeds the ray batch");

  TransportStats local;
  const Vec3 origin = position + normal * epsilon;
  std::fill(row.begin(), row.end(), 0.0f);
  RayBatch batch;
  for (int m = 0; m < cubemap.size(); ++m) {
    if (BelowHorizon(pattern, m, normal)) {
      ++local.texels_culled;
      row[m] = static_cast<float>(pattern.per_texel);  // V := 1 below the horizon
      continue;
    }
    if (batch.count + pattern.per_texel > kBatch) Flush(caster, origin, batch, row, local, true);
    row[m] += static_cast<float>(AddTexel(pattern, m, normal, batch));
  }
  Flush(caster, origin, batch, row, local, true);
  const float inv_k = 1.0f / static_cast<float>(pattern.per_texel);
  for (float& v : row) v *= inv_k;

  if (stats) {
    stats->rays_traced += local.rays_traced;
    stats->rays_occluded += local.rays_occluded;
    stats->texels_culled += local.texels_culled;
  }
}

}  // namespace wavebake
