#pragma once
// The per-job geometry of visibility refinement (core/transport/refined_row.h): a
// quadtree of texel blocks on every cube face, the 8 neighbours of every
// block at every level (across face edges too), the texel whose jittered ray
// 0 probes each block, and the exact irradiance vector of every texel
// (core/directions/texel_irradiance.h). Depends on the cubemap, the jitter pattern and
// the options only, so
// every worker builds the same plan; read-only once built.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/directions/cubemap.h"
#include "core/directions/jitter_pattern.h"
#include "core/util/vec3.h"

namespace wavebake {

// How coarse the first probes are and which guards against thin occluders
// (features that slip between coarse probes) are on. The defaults are the
// bake's; the others exist so tests and benchmarks can show what each guard
// buys.
struct RefineOptions {
  // Texels between first probes along a face edge (power of two ≥ 1, capped
  // at N/8 so that they are never more than ~11° apart): the finest starting
  // spacing. Blocks of start_spacing² texels are probed by one ray each
  // before anything is subdivided.
  int start_spacing = 4;
  // Each start block's probe sits at a different offset, (by, bx + by) mod
  // spacing, a lattice that no straight strip of one texel column (row,
  // diagonal) avoids for more than `start_spacing` blocks; false: every
  // probe at offset 0, a regular lattice a thin axis-aligned occluder can
  // slip through entirely.
  bool stagger = true;
  // Follow silhouettes texel by texel: a traced texel whose rays disagree, or
  // which disagrees with a neighbour, has its untraced neighbours traced, and
  // so on, so an occluder found at one probe is traced along its whole extent.
  bool follow = true;
};

class RefinePlan {
 public:
  RefinePlan(const Cubemap& cubemap, const JitterPattern& pattern, const RefineOptions& options);

  const RefineOptions& options() const { return options_; }
  int start_level() const { return start_level_; }  // log2 of the start spacing
  int n() const { return n_; }
  int log2_n() const { return log2_n_; }
  // Blocks of level l are the texels of Cubemap(N >> l): index
  // (face·n_l + by)·n_l + bx covers texels [bx·2^l, (bx+1)·2^l) × (same in y).
  int BlocksPerEdge(int level) const { return n_ >> level; }
  int BlockCount(int level) const { return 6 * BlocksPerEdge(level) * BlocksPerEdge(level); }
  // The texel whose ray 0 probes the block: at offset (by0, bx0 + by0) mod
  // spacing inside its start block (bx0, by0), or 0 without stagger, taken
  // mod the block size. A block's anchor is therefore the anchor of one of
  // its children, so a probe is traced once for all levels. Arithmetic, no
  // table: the refinement is bound by memory traffic, not by these adds.
  int32_t AnchorAt(int level, int face, int bx, int by) const {
    const int shift = start_level_ - level, size_mask = (1 << level) - 1;
    const int sx = bx >> shift, sy = by >> shift, spacing_mask = (1 << start_level_) - 1;
    const int ox = options_.stagger ? sy & spacing_mask : 0;
    const int oy = options_.stagger ? (sx + sy) & spacing_mask : 0;
    const int x = (bx << level) + (ox & size_mask), y = (by << level) + (oy & size_mask);
    return (((face << log2_n_) + y) << log2_n_) + x;
  }
  // The same, from a table (level 0: the texel itself): the refinement looks
  // up the anchors of every block it visits and of their 8 neighbours.
  int32_t Anchor(int level, int block) const { return level == 0 ? block : anchors_[level][block]; }
  // f(anchor) for the anchors of the block's 8 neighbours at its own level,
  // across face edges too (a cube-corner block has one neighbour twice: the
  // diagonal beyond the corner maps onto an edge neighbour), until f returns
  // false; true if it never did. At level 0 anchors are the texels themselves.
  template <class F>
  bool AllNeighbourAnchors(int level, int block, F f) const {
    const int log2 = log2_n_ - level, n = 1 << log2, r = block & ((1 << 2 * log2) - 1);
    const int bx = r & (n - 1), by = r >> log2;
    if (bx > 0 && by > 0 && bx < n - 1 && by < n - 1) {
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if ((dx | dy) != 0 && !f(Anchor(level, block + dy * n + dx))) return false;
      return true;
    }
    const int face = block >> 2 * log2;
    const int32_t* across = &edges_[level][(size_t(face) * 4 * n + EdgeSlot(bx, by, n)) * 8];
    for (int i = 0; i < 8; ++i)
      if (!f(across[i])) return false;
    return true;
  }
  // That ray's direction.
  const Vec3& ProbeDirection(int level, int block) const {
    return level == 0 ? texel_rays_[size_t(MortonSlot(0, block)) * per_texel_]
                      : probe_direction_[level][MortonSlot(level, block)];
  }
  // The blocks of the start level, each face in Z order (the order rays are
  // traced in: neighbouring probes share packets).
  std::span<const int32_t> StartBlocks() const { return start_blocks_; }
  // The K jittered directions of texel m (JitterPattern::Direction(m, k)).
  std::span<const Vec3> TexelRays(int m) const {
    return std::span(texel_rays_).subspan(size_t(MortonSlot(0, m)) * per_texel_, per_texel_);
  }
  // Φ_m (core/directions/texel_irradiance.h): the transport entry of a fully visible
  // texel entirely above the horizon of n is n·Φ_m.
  Vec3 Irradiance(int m) const { return {phi_x_[m], phi_y_[m], phi_z_[m]}; }
  float IrradianceAt(int m, Vec3 n) const {
    return n.x * phi_x_[m] + n.y * phi_y_[m] + n.z * phi_z_[m];
  }

  // The point of face f at texel-corner coordinates (x, y) ∈ [0, N]² is
  // origin + x·dx + y·dy (Cubemap::FacePoint is affine in s, t), so n·p is
  // affine in (x, y) and its sign over a block follows from its corners
  // without touching memory.
  struct FaceFrame {
    std::array<double, 3> origin, dx, dy;
  };
  const FaceFrame& Frame(int face) const { return frames_[face]; }

  // Per-block data is stored in Z order within each face, so that the four
  // children of a block (probed together) share cache lines: refinement
  // touches a scattered few percent of the texels, and would otherwise miss
  // the cache on nearly every one.
  int MortonSlot(int level, int block) const {
    const int log2 = log2_n_ - level, n = 1 << log2, r = block & ((1 << 2 * log2) - 1);
    return ((block >> 2 * log2) << 2 * log2) | Interleave(r & (n - 1), r >> log2);
  }
  static int Interleave(int x, int y) { return kSpread[x] | (kSpread[y] << 1); }
  static const std::array<uint16_t, 256> kSpread;  // bits of x at the even positions

 private:
  // The blocks along a face's edges, numbered 0..4n-1 (top row, bottom
  // row, left column, right column; corners count in the rows).
  static int EdgeSlot(int bx, int by, int n) {
    return by == 0 ? bx : by == n - 1 ? n + bx : bx == 0 ? 2 * n + by : 3 * n + by;
  }
  RefineOptions options_;
  int n_ = 0, log2_n_ = 0;
  int start_level_ = 0;
  // Per level: the 8 neighbour anchors of every edge block, [face][slot][8].
  std::vector<std::vector<int32_t>> edges_;
  // Per level ≥ 1: AnchorAt of every block, by block index.
  std::vector<std::vector<int32_t>> anchors_;
  // Per level ≥ 1: ray 0 of every block's anchor, Z order.
  std::vector<std::vector<Vec3>> probe_direction_;
  std::vector<Vec3> texel_rays_;  // the pattern's directions, texels in Z order
  std::vector<int32_t> start_blocks_;
  int per_texel_ = 0;
  std::vector<float> phi_x_, phi_y_, phi_z_;
  std::array<FaceFrame, 6> frames_;
};

}  // namespace wavebake
