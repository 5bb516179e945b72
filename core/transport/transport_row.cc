#include "core/transport/transport_row.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>

#include "core/util/check_or_die.h"

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
  float cosine[kBatch];  // n·ω_k > 0
  uint8_t occluded[kBatch];
  int count = 0;
  // The batch's texels in order and how many rays each has in it, one run
  // after another (a texel is never split between batches).
  int32_t run_texel[kBatch];
  int32_t run_length[kBatch];
  int runs = 0;
};

// The even bits of z packed together: the x of Z-order index z (y is
// EvenBits(z >> 1)). z < 2^16 (N ≤ 256).
constexpr std::array<uint8_t, 256> kEvenBits = [] {
  std::array<uint8_t, 256> t{};
  for (int b = 0; b < 256; ++b)
    for (int i = 0; i < 4; ++i) t[b] |= ((b >> (2 * i)) & 1) << i;
  return t;
}();
int EvenBits(int z) { return kEvenBits[z & 0xFF] | kEvenBits[(z >> 8) & 0xFF] << 4; }

// A texel is the conic hull of its 4 corner directions, so if none of them is
// above the horizon no direction inside it is: the texel is exactly 0 and
// needs no rays. The test is on the pattern's float corners.
bool CornersBelow(const JitterPattern& p, int m, Vec3 n) {
  const Vec3* c = &p.corners[static_cast<size_t>(m) * 4];
  return Dot(n, c[0]) <= 0 && Dot(n, c[1]) <= 0 && Dot(n, c[2]) <= 0 && Dot(n, c[3]) <= 0;
}

// The same answer mostly without touching the corners: n·p is affine on a
// face in texel-corner coordinates (Cubemap::FacePoint), so its largest value
// over a texel is at the corner the slopes pick, and the texel is below the
// horizon iff that is ≤ 0. Clear cases (beyond kMargin, far above the float
// corners' rounding) are decided here; texels with a corner within kMargin of
// the horizon are left to CornersBelow.
class HorizonTest {
 public:
  HorizonTest(int n, Vec3 normal) {
    const double nd[3] = {normal.x, normal.y, normal.z};
    auto dot = [&](const std::array<double, 3>& v) {
      return nd[0] * v[0] + nd[1] * v[1] + nd[2] * v[2];
    };
    for (int f = 0; f < 6; ++f) {
      const double o = dot(Cubemap::FacePoint(f, 0, 0));
      line_[f] = {o, (dot(Cubemap::FacePoint(f, 1, 0)) - o) / n,
                  (dot(Cubemap::FacePoint(f, 0, 1)) - o) / n};
    }
  }
  // Whether a whole face is clearly above or below the horizon (n·p is
  // affine on it, so its extremes are at the face's corners), which settles
  // every texel of it without a test each; kCrossing otherwise.
  enum class Face { kAbove, kBelow, kCrossing };
  Face FaceClass(int face, int n) const {
    const Line& l = line_[face];
    const double lo = l.a + n * (std::min(l.b, 0.0) + std::min(l.c, 0.0));
    const double hi = l.a + n * (std::max(l.b, 0.0) + std::max(l.c, 0.0));
    return lo > 2 * kMargin ? Face::kAbove : hi < -2 * kMargin ? Face::kBelow : Face::kCrossing;
  }
  bool Below(const JitterPattern& p, int m, Vec3 normal, int face, int x, int y) const {
    const Line& l = line_[face];
    const double hi = l.a + l.b * x + l.c * y + std::max(l.b, 0.0) + std::max(l.c, 0.0);
    if (hi > kMargin) return false;
    if (hi < -kMargin) return true;
    return CornersBelow(p, m, normal);
  }

 private:
  static constexpr double kMargin = 1e-5;
  struct Line {
    double a, b, c;  // n·p at texel corner (x, y): a + b·x + c·y
  };
  std::array<Line, 6> line_;
};

// Four floats in one register (GCC/Clang vector extension; SSE on x86-64).
using Float4 = float __attribute__((vector_size(16)));
Float4 Load4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
void Store4(float* p, Float4 v) { std::memcpy(p, &v, sizeof v); }

// Appends texel m's directions that are above the horizon; the ones below
// contribute max(0, n·ω) = 0 whatever V is, so they are not traced. Returns
// how many were below.
[[gnu::always_inline]] inline int AddTexel(const JitterPattern& p, int m, Vec3 n, RayBatch& b) {
  const size_t first = static_cast<size_t>(m) * p.per_texel;
  int below = 0, k = 0;
  // Four rays at a time while all four are above the horizon (nearly every
  // texel the row traces): four-wide loads, products and stores, no branch
  // per ray. Each lane is the same float expression as the loop below, so
  // the row is the same bits.
  for (; k + 4 <= p.per_texel; k += 4) {
    const Float4 x = Load4(&p.x[first + k]), y = Load4(&p.y[first + k]), z = Load4(&p.z[first + k]);
    const Float4 c = n.x * x + n.y * y + n.z * z;
    const auto above = c > Float4{};  // lanes of -1 (true) or 0
    if (!(above[0] & above[1] & above[2] & above[3])) break;
    const int at = b.count;
    Store4(&b.x[at], x);
    Store4(&b.y[at], y);
    Store4(&b.z[at], z);
    Store4(&b.cosine[at], c);
    b.count = at + 4;
  }
  for (; k < p.per_texel; ++k) {
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
    ++b.count;
  }
  if (below < p.per_texel) {
    b.run_texel[b.runs] = m;
    b.run_length[b.runs] = p.per_texel - below;
    ++b.runs;
  }
  return below;
}

// What a texel's sum is multiplied by once its rays are added, so that the
// row needs no pass of its own for it: Ω_m · factor (the diffuse row), or 1.
struct TexelScale {
  const float* solid_angle = nullptr;  // null: 1
  float factor = 1;
  float At(int32_t m) const { return solid_angle ? solid_angle[m] * factor : 1.0f; }
};

// Traces the batch and adds the cosines of the unoccluded rays to their
// texels (with `count_only`, 1 per unoccluded ray instead: visibility), then
// scales each texel. A texel's rays are contiguous in the batch and added in
// k order in a register (not through memory, where each add would wait for
// the last one's store), so the sum is deterministic.
void Flush(const RayCaster& caster, Vec3 origin, RayBatch& b, std::span<float> row,
           TransportStats& stats, TexelScale scale, bool count_only = false) {
  if (b.count == 0) return;
  const size_t n = static_cast<size_t>(b.count);
  caster.OccludedFan(origin, {{b.x, n}, {b.y, n}, {b.z, n}}, 0,
                     std::numeric_limits<float>::infinity(), {b.occluded, n});
  // Branch-free (which rays are blocked is unpredictable): an occluded ray
  // adds +0, which leaves a sum of positive cosines bit for bit unchanged.
  float* out = row.data();
  uint64_t occluded = 0;
  for (int r = 0, i = 0; r < b.runs; ++r) {
    const int32_t m = b.run_texel[r];
    float sum = out[m];
    for (const int end = i + b.run_length[r]; i < end; ++i) {
      occluded += b.occluded[i];
      sum += b.occluded[i] ? 0.0f : count_only ? 1.0f : b.cosine[i];
    }
    out[m] = sum * scale.At(m);
  }
  stats.rays_occluded += occluded;
  stats.rays_traced += n;
  b.count = 0;
  b.runs = 0;
}

}  // namespace

uint64_t BruteForceRays(const Cubemap& cubemap, const JitterPattern& pattern, Vec3 normal) {
  const int n = cubemap.n();
  const HorizonTest horizon(n, normal);
  uint64_t rays = 0;
  for (int face = 0; face < 6; ++face) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const int m = (face * n + y) * n + x;
        if (horizon.Below(pattern, m, normal, face, x, y)) continue;
        const size_t first = static_cast<size_t>(m) * pattern.per_texel;
        for (int k = 0; k < pattern.per_texel; ++k) {
          const size_t i = first + k;
          rays += normal.x * pattern.x[i] + normal.y * pattern.y[i] + normal.z * pattern.z[i] > 0;
        }
      }
    }
  }
  return rays;
}

namespace {

// The row both overloads trace: `for_each_texel(trace, cull)` visits every
// texel once, in the order rays should be traced in, calling trace(m) for
// texels above the horizon and cull() for the others. Each texel's rays add
// up in k order, so the row does not depend on the visiting order.
template <class ForEachTexel>
void TraceRow(const RayCaster& caster, const JitterPattern& pattern, Vec3 position, Vec3 normal,
              float epsilon, std::span<float> row, TransportStats* stats,
              ForEachTexel for_each_texel) {
  CheckOrDie("TransportRow", row.size() == static_cast<size_t>(pattern.texels()),
             "row size differs from M");
  CheckOrDie("TransportRow", pattern.per_texel <= kBatch, "supersampling exceeds the ray batch");

  TransportStats local;
  const Vec3 origin = position + normal * epsilon;  // DESIGN.md §1: rays start at x + ε n
  std::fill(row.begin(), row.end(), 0.0f);
  // Ω_m · (1/K) · f_r with f_r = 1/π (albedo factored out, DESIGN.md §1),
  // applied as each texel's rays are added up.
  const TexelScale scale{pattern.solid_angle.data(),
                         static_cast<float>(1.0 / (pattern.per_texel * std::numbers::pi))};
  RayBatch batch;
  for_each_texel(
      [&](int m) {
        if (batch.count + pattern.per_texel > kBatch)
          Flush(caster, origin, batch, row, local, scale);
        AddTexel(pattern, m, normal, batch);
      },
      [&] { ++local.texels_culled; });
  Flush(caster, origin, batch, row, local, scale);

  if (stats) {
    stats->rays_traced += local.rays_traced;
    stats->rays_occluded += local.rays_occluded;
    stats->texels_culled += local.texels_culled;
  }
}

}  // namespace

void TransportRow(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
                  Vec3 position, Vec3 normal, float epsilon, std::span<float> row,
                  TransportStats* stats) {
  CheckOrDie("TransportRow", pattern.n == cubemap.n() && pattern.texels() == cubemap.size(),
             "jitter pattern was made for another cubemap");
  // Texels in Z order within each face (2×2 blocks, then 4×4, ...): packets
  // of neighbouring directions traverse the BVH together (bench/transport.cc:
  // 11 % more rays/s than row order).
  const int n = cubemap.n();
  const HorizonTest horizon(n, normal);
  TraceRow(caster, pattern, position, normal, epsilon, row, stats, [&](auto trace, auto cull) {
    for (int face = 0; face < 6; ++face) {
      const HorizonTest::Face whole = horizon.FaceClass(face, n);
      for (int z = 0; z < n * n; ++z) {
        const int x = EvenBits(z), y = EvenBits(z >> 1), m = (face * n + y) * n + x;
        const bool below = whole == HorizonTest::Face::kCrossing
                               ? horizon.Below(pattern, m, normal, face, x, y)
                               : whole == HorizonTest::Face::kBelow;
        if (below) {
          cull();
        } else {
          trace(m);
        }
      }
    }
  });
}

void TransportRow(const RayCaster& caster, const JitterPattern& pattern, Vec3 position, Vec3 normal,
                  float epsilon, std::span<float> row, TransportStats* stats) {
  TraceRow(caster, pattern, position, normal, epsilon, row, stats, [&](auto trace, auto cull) {
    for (int m = 0; m < pattern.texels(); ++m) {
      if (CornersBelow(pattern, m, normal)) {
        cull();
      } else {
        trace(m);
      }
    }
  });
}

void VisibilityRow(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
                   Vec3 position, Vec3 normal, float epsilon, std::span<float> row,
                   TransportStats* stats) {
  CheckOrDie("TransportRow", row.size() == static_cast<size_t>(cubemap.size()),
             "row size differs from M");
  CheckOrDie("TransportRow", pattern.n == cubemap.n() && pattern.texels() == cubemap.size(),
             "jitter pattern was made for another cubemap");
  CheckOrDie("TransportRow", pattern.per_texel <= kBatch, "supersampling exceeds the ray batch");

  TransportStats local;
  const Vec3 origin = position + normal * epsilon;
  std::fill(row.begin(), row.end(), 0.0f);
  RayBatch batch;
  for (int m = 0; m < cubemap.size(); ++m) {
    if (CornersBelow(pattern, m, normal)) {
      ++local.texels_culled;
      row[m] = static_cast<float>(pattern.per_texel);  // V := 1 below the horizon
      continue;
    }
    if (batch.count + pattern.per_texel > kBatch)
      Flush(caster, origin, batch, row, local, TexelScale{}, true);
    row[m] += static_cast<float>(AddTexel(pattern, m, normal, batch));
  }
  Flush(caster, origin, batch, row, local, TexelScale{}, true);
  const float inv_k = 1.0f / static_cast<float>(pattern.per_texel);
  for (float& v : row) v *= inv_k;

  if (stats) {
    stats->rays_traced += local.rays_traced;
    stats->rays_occluded += local.rays_occluded;
    stats->texels_culled += local.texels_culled;
  }
}

}  // namespace wavebake
