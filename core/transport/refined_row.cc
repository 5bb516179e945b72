#include "core/transport/refined_row.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "core/directions/texel_irradiance.h"
#include "core/util/check_or_die.h"

namespace wavebake {
namespace {

// What is known of a texel. "Decided" texels got their value from a uniform
// block, "traced" ones from their own K rays.
enum TexelState : uint8_t {
  kOpen,  // inside a block still being refined
  kBelow,
  kDecidedVisible,
  kDecidedOccluded,
  kTracedVisible,
  kTracedOccluded,
  kTracedMixed,
  kTracedNone,  // traced, but none of its rays is above the horizon
  kQueued,      // decided, waiting to be traced by silhouette following
};

constexpr int8_t kUntraced = -1, kProbeBelow = -2;

// 1 visible, 0 occluded, 2 mixed, -1 nothing to compare.
int ClassOf(uint8_t s) {
  switch (s) {
    case kDecidedVisible:
    case kTracedVisible:
      return 1;
    case kDecidedOccluded:
    case kTracedOccluded:
      return 0;
    case kTracedMixed:
      return 2;
    default:
      return -1;
  }
}

enum class Horizon { kBelow, kAbove, kCrossing };

// Rays per Embree call, as in TransportRow: a whole texel for K ≤ 256.
constexpr int kRefineBatch = 512;

class RowRefiner {
 public:
  RowRefiner(const RayCaster& caster, const Cubemap& cubemap, const JitterPattern& pattern,
             const RefinePlan& plan, Vec3 origin, Vec3 normal, std::span<float> row,
             RefineScratch& scratch)
      : caster_(caster),
        cubemap_(cubemap),
        p_(pattern),
        plan_(plan),
        origin_(origin),
        n_(normal),
        row_(row),
        s_(scratch) {
    const double nd[3] = {normal.x, normal.y, normal.z};
    auto dot = [&](const std::array<double, 3>& v) {
      return nd[0] * v[0] + nd[1] * v[1] + nd[2] * v[2];
    };
    for (int f = 0; f < 6; ++f) {
      const RefinePlan::FaceFrame& frame = plan.Frame(f);
      horizon_[f] = {dot(frame.origin), dot(frame.dx), dot(frame.dy)};
    }
  }

  void Run() {
    s_.state.assign(cubemap_.size(), kOpen);
    s_.probe.assign(cubemap_.size(), kUntraced);
    s_.vote.assign(cubemap_.size(), -1);
    // Raw pointers: byte stores may alias anything, and would make the
    // compiler reload vector data pointers in every loop.
    state_ = s_.state.data();
    probe_ = s_.probe.data();
    vote_ = s_.vote.data();
    // Every texel's value is written once it is culled, decided or traced:
    // the row needs no clearing first.
    s_.active.assign(plan_.StartBlocks().begin(), plan_.StartBlocks().end());
    for (int level = plan_.start_level(); level >= 0; --level) RefineLevel(level);
    TraceTexels(s_.to_trace);
    if (plan_.options().follow) Follow();
  }

  TransportStats stats;

 private:
  struct Block {
    int face, x0, y0, size;
  };
  Block BlockAt(int level, int block) const {
    const int log2 = plan_.log2_n() - level, r = block & ((1 << 2 * log2) - 1);
    return {block >> 2 * log2, (r & ((1 << log2) - 1)) << level, (r >> log2) << level, 1 << level};
  }
  int TexelIndex(int face, int x, int y) const {
    return (((face << plan_.log2_n()) + y) << plan_.log2_n()) + x;
  }

  // A block is the conic hull of its 4 corner directions, so the signs of
  // n·corner bound every direction inside it; n·p is affine on each face
  // (RefinePlan::FaceFrame), so its extremes over the block are at corners
  // picked by the signs of its slopes.
  Horizon HorizonOf(int level, int block) const {
    const Block b = BlockAt(level, block);
    const HorizonLine& h = horizon_[b.face];
    const double at = h.a + h.b * b.x0 + h.c * b.y0;
    const double bx = h.b * b.size, cy = h.c * b.size;
    const double lo = at + std::min(bx, 0.0) + std::min(cy, 0.0);
    const double hi = at + std::max(bx, 0.0) + std::max(cy, 0.0);
    return hi <= 0 ? Horizon::kBelow : lo > 0 ? Horizon::kAbove : Horizon::kCrossing;
  }

  // The block's texels, row by row: f(first texel, count).
  template <class F>
  void ForRows(int level, int block, F f) const {
    const Block b = BlockAt(level, block);
    for (int y = b.y0; y < b.y0 + b.size; ++y) f(TexelIndex(b.face, b.x0, y), size_t(b.size));
  }

  void Decide(int level, int block, bool visible, bool crossing) {
    if (crossing) return DecideCrossing(level, block, visible);
    float* row = row_.data();
    const RefinePlan& plan = plan_;
    const Vec3 n = n_;
    ForRows(level, block, [&](int first, size_t count) {
      std::memset(state_ + first, visible ? kDecidedVisible : kDecidedOccluded, count);
      std::memset(vote_ + first, visible ? 1 : 0, count);
      if (visible) {
        for (int m = first, end = first + int(count); m < end; ++m)
          row[m] = plan.IrradianceAt(m, n);
      } else {
        std::fill_n(row + first, count, 0.0f);
      }
    });
  }

  // A uniform block the horizon crosses, texel by texel: those below it are
  // 0 (and culled, as brute force culls them), the others get the block's
  // class and, if visible, I_m(n) — n·Φ_m entirely above the horizon, the
  // integral over the part above it where the horizon crosses the texel.
  void DecideCrossing(int level, int block, bool visible) {
    ForRows(level, block, [&](int first, size_t count) {
      for (int m = first, end = first + int(count); m < end; ++m) {
        const Horizon h = HorizonOf(0, m);
        if (h == Horizon::kBelow) {
          state_[m] = kBelow;
          vote_[m] = -1;
          row_[m] = 0;
          ++stats.texels_culled;
          continue;
        }
        state_[m] = visible ? kDecidedVisible : kDecidedOccluded;
        vote_[m] = visible ? 1 : 0;
        row_[m] = !visible ? 0.0f : h == Horizon::kAbove ? plan_.IrradianceAt(m, n_) : Clipped(m);
      }
    });
  }

  // I_m(n) of a texel the horizon crosses (core/directions/texel_irradiance.h).
  float Clipped(int m) const {
    return static_cast<float>(ClippedTexelIrradiance(cubemap_, m, n_, plan_.Irradiance(m)));
  }

  // Probe, neighbours' probes (or decided values): all the same.
  bool Uniform(int level, int block) const {
    const int p = probe_[plan_.Anchor(level, block)];
    if (p < 0) return false;
    // An open neighbour is refined at this same level: its probe is traced.
    return plan_.AllNeighbourAnchors(level, block, [&](int32_t a) {
      const int q = vote_[a];
      return q < 0 || q == p;
    });
  }

  void RefineLevel(int level) {
    s_.next.clear();
    // Blocks below the horizon are 0 and drop out; the rest get probes.
    size_t kept = 0;
    s_.crossing.clear();
    for (int32_t b : s_.active) {
      const Horizon h = HorizonOf(level, b);
      if (h == Horizon::kBelow) {
        ForRows(level, b, [&](int first, size_t count) {
          std::memset(state_ + first, kBelow, count);
          std::fill_n(row_.data() + first, count, 0.0f);
          std::memset(vote_ + first, -1, count);
        });
        stats.texels_culled += size_t(1) << (2 * level);
      } else {
        s_.active[kept++] = b;
        s_.crossing.push_back(h == Horizon::kCrossing);
      }
    }
    s_.active.resize(kept);
    // The probe directions are scattered reads: ask for them ahead.
    constexpr size_t kAhead = 8;
    for (size_t i = 0; i < s_.active.size(); ++i) {
      if (i + kAhead < s_.active.size())
        __builtin_prefetch(&plan_.ProbeDirection(level, s_.active[i + kAhead]));
      AddProbe(level, s_.active[i]);
    }
    FlushProbes();
    for (size_t i = 0; i < s_.active.size(); ++i) {
      const int32_t b = s_.active[i];
      if (Uniform(level, b)) {
        Decide(level, b, probe_[plan_.Anchor(level, b)] == 1, s_.crossing[i]);
      } else if (level == 0) {
        s_.to_trace.push_back(b);
      } else {  // the 4 children, by shifts (blocks per edge is 2^log2)
        const int log2 = plan_.log2_n() - level, r = b & ((1 << 2 * log2) - 1);
        const int face = b >> 2 * log2, x = r & ((1 << log2) - 1), y = r >> log2;
        const int child_n = 2 << log2;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx)
            s_.next.push_back((face * child_n + 2 * y + dy) * child_n + 2 * x + dx);
      }
    }
    s_.active.swap(s_.next);
  }

  // --- rays ----------------------------------------------------------------

  struct Rays {
    alignas(64) float x[kRefineBatch];
    alignas(64) float y[kRefineBatch];
    alignas(64) float z[kRefineBatch];
    float cosine[kRefineBatch];
    int32_t owner[kRefineBatch];  // probe texel, or slot of a traced texel
    uint8_t occluded[kRefineBatch];
    int count = 0;
  };

  void Push(Vec3 d, float cosine, int32_t owner) {
    rays_.x[rays_.count] = d.x;
    rays_.y[rays_.count] = d.y;
    rays_.z[rays_.count] = d.z;
    rays_.cosine[rays_.count] = cosine;
    rays_.owner[rays_.count] = owner;
    ++rays_.count;
  }

  // Every kernel of RayCaster::OccludedFan measured the same on these rays
  // (bench/refine.cc): packets of nearby probes and of whole texels.
  void Trace() {
    const size_t n = rays_.count;
    caster_.OccludedFan(origin_, {{rays_.x, n}, {rays_.y, n}, {rays_.z, n}}, 0,
                        std::numeric_limits<float>::infinity(), {rays_.occluded, n});
    stats.rays_traced += n;
    for (size_t i = 0; i < n; ++i) stats.rays_occluded += rays_.occluded[i];
  }

  void AddProbe(int level, int32_t block) {
    const int32_t texel = plan_.Anchor(level, block);
    if (probe_[texel] != kUntraced) return;
    const Vec3 d = plan_.ProbeDirection(level, block);
    const float c = Dot(n_, d);
    if (!(c > 0)) {
      probe_[texel] = kProbeBelow;
      return;
    }
    if (rays_.count == kRefineBatch) FlushProbes();
    Push(d, c, texel);
  }

  void FlushProbes() {
    if (rays_.count == 0) return;
    Trace();
    for (int i = 0; i < rays_.count; ++i)
      probe_[rays_.owner[i]] = vote_[rays_.owner[i]] = rays_.occluded[i] ? 0 : 1;
    rays_.count = 0;
  }

  void TraceTexels(std::span<const int32_t> texels) {
    for (int32_t t : texels) {
      if (rays_.count + p_.per_texel > kRefineBatch) FlushTexels();
      RefineSlot slot{t, HorizonOf(0, t) == Horizon::kAbove};
      const int owner = static_cast<int>(s_.slots.size());
      const std::span<const Vec3> dirs = plan_.TexelRays(t);
      for (int k = 0; k < p_.per_texel; ++k) {
        const Vec3 d = dirs[k];
        const float c = Dot(n_, d);
        if (!(c > 0)) continue;
        ++slot.rays_above;
        slot.sum_c += c;
        if (k == 0 && probe_[t] >= 0) {  // the probe is this ray
          if (probe_[t] == 1) ++slot.visible, slot.sum_vc += c;
          continue;
        }
        Push(d, c, owner);
      }
      s_.slots.push_back(slot);
    }
    FlushTexels();
  }

  void FlushTexels() {
    if (rays_.count > 0) Trace();
    // Rays of one texel are in k order, so the sums are the same every time.
    for (int i = 0; i < rays_.count; ++i) {
      if (rays_.occluded[i]) continue;
      RefineSlot& slot = s_.slots[rays_.owner[i]];
      ++slot.visible;
      slot.sum_vc += rays_.cosine[i];
    }
    for (const RefineSlot& slot : s_.slots) Finish(slot);
    rays_.count = 0;
    s_.slots.clear();
  }

  void Finish(const RefineSlot& slot) {
    const int32_t m = slot.texel;
    if (slot.rays_above == 0) {
      state_[m] = kTracedNone;
      row_[m] = 0;
      return;
    }
    state_[m] = slot.visible == slot.rays_above ? kTracedVisible
                : slot.visible == 0             ? kTracedOccluded
                                                : kTracedMixed;
    if (slot.visible == 0) {
      row_[m] = 0;
      return;
    }
    // I_m(n) times the cosine-weighted visible fraction of the rays above the horizon.
    const float exact = slot.above ? plan_.IrradianceAt(m, n_) : Clipped(m);
    row_[m] = slot.visible == slot.rays_above ? exact : exact * (slot.sum_vc / slot.sum_c);
  }

  // --- silhouette following ------------------------------------------------

  // A traced texel whose rays disagree, or that disagrees with a neighbour.
  bool Boundary(int32_t t) const {
    const int c = ClassOf(state_[t]);
    if (c == 2) return true;
    if (c < 0) return false;
    return !plan_.AllNeighbourAnchors(0, t, [&](int32_t nb) {
      const int q = ClassOf(state_[nb]);
      return !((q == 0 || q == 1) && q != c);
    });
  }

  void Follow() {
    s_.frontier.clear();
    for (int32_t t : s_.to_trace)
      if (Boundary(t)) s_.frontier.push_back(t);
    while (!s_.frontier.empty()) {
      s_.next.clear();
      for (int32_t t : s_.frontier) {
        const int c = ClassOf(state_[t]);
        plan_.AllNeighbourAnchors(0, t, [&](int32_t nb) {
          const uint8_t s = state_[nb];
          if ((s == kDecidedVisible || s == kDecidedOccluded) && (c == 2 || ClassOf(s) != c)) {
            state_[nb] = kQueued;  // decided, and not in agreement with a pure texel
            s_.next.push_back(nb);
          }
          return true;
        });
      }
      // Z order, as everything else is traced: coherent packets.
      std::sort(s_.next.begin(), s_.next.end(), [&](int32_t a, int32_t b) {
        return plan_.MortonSlot(0, a) < plan_.MortonSlot(0, b);
      });
      TraceTexels(s_.next);
      s_.frontier.clear();
      for (int32_t t : s_.next)
        if (Boundary(t)) s_.frontier.push_back(t);
    }
  }

  const RayCaster& caster_;
  const Cubemap& cubemap_;
  const JitterPattern& p_;
  const RefinePlan& plan_;
  Vec3 origin_, n_;
  std::span<float> row_;
  RefineScratch& s_;
  uint8_t* state_ = nullptr;
  int8_t* probe_ = nullptr;
  // While the levels are refined: what texel a says to a neighbouring block's
  // uniformity test — its probe while it is open, its class once decided, -1
  // (nothing) below the horizon or untraced. Kept beside state_ and probe_ so
  // that the test reads one byte per neighbour.
  int8_t* vote_ = nullptr;
  struct HorizonLine {
    double a, b, c;  // n·p at texel corner (x, y) of a face: a + b·x + c·y
  };
  std::array<HorizonLine, 6> horizon_;
  Rays rays_;
};

}  // namespace

void RefinedTransportRow(const RayCaster& caster, const Cubemap& cubemap,
                         const JitterPattern& pattern, const RefinePlan& plan, Vec3 position,
                         Vec3 normal, float epsilon, std::span<float> row, TransportStats* stats,
                         RefineScratch& scratch) {
  CheckOrDie("RefinedTransportRow", row.size() == static_cast<size_t>(cubemap.size()),
             "row size differs from M");
  CheckOrDie("RefinedTransportRow", pattern.n == cubemap.n() && pattern.texels() == cubemap.size(),
             "jitter pattern was made for another cubemap");
  CheckOrDie("RefinedTransportRow", plan.n() == cubemap.n(),
             "refinement plan was made for another cubemap");
  CheckOrDie("RefinedTransportRow", pattern.per_texel <= kRefineBatch,
             "supersampling exceeds the ray batch");
  scratch.to_trace.clear();
  // DESIGN.md §1: rays start at x + ε n.
  RowRefiner refiner(caster, cubemap, pattern, plan, position + normal * epsilon, normal, row,
                     scratch);
  refiner.Run();
  if (stats) {
    stats->rays_traced += refiner.stats.rays_traced;
    stats->rays_occluded += refiner.stats.rays_occluded;
    stats->texels_culled += refiner.stats.texels_culled;
  }
}

}  // namespace wavebake
