#include "core/transport/refine_plan.h"

#include <algorithm>

#include "core/directions/texel_irradiance.h"

namespace wavebake {
namespace {

constexpr int kOffsets[8][2] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0},
                                {1, 0},   {-1, 1}, {0, 1},  {1, 1}};

// The block beside (face, x, y) in the cubemap of blocks; beyond a face edge,
// the block whose square holds the direction through the would-be centre
// there (the face plane extends past its edge onto the next face).
int32_t NeighbourOf(const Cubemap& blocks, int face, int x, int y) {
  const int n = blocks.n();
  if (x >= 0 && x < n && y >= 0 && y < n) return blocks.Index({face, x, y});
  return blocks.Lookup(Cubemap::FaceDirection(face, (x + 0.5) / n, (y + 0.5) / n));
}

constexpr std::array<uint16_t, 256> SpreadBits() {
  std::array<uint16_t, 256> out{};
  for (int v = 0; v < 256; ++v)
    for (int b = 0; b < 8; ++b) out[v] |= ((v >> b) & 1) << (2 * b);
  return out;
}

int FloorLog2(int v) {
  int l = 0;
  while ((2 << l) <= v) ++l;
  return l;
}

}  // namespace

const std::array<uint16_t, 256> RefinePlan::kSpread = SpreadBits();

RefinePlan::RefinePlan(const Cubemap& cubemap, const JitterPattern& pattern,
                       const RefineOptions& options)
    : options_(options), n_(cubemap.n()), log2_n_(FloorLog2(cubemap.n())) {
  // At most N/8 texels (a face is 90°, so ~11°) between first probes: at
  // coarse N a few texels are a large angle, and a 4-texel spacing at N = 8
  // let a disk of 45° slip between the probes entirely.
  start_level_ = FloorLog2(std::clamp(std::min(options.start_spacing, n_ / 8), 1, n_));
  options_.start_spacing = 1 << start_level_;
  per_texel_ = pattern.per_texel;
  texel_rays_.resize(size_t(cubemap.size()) * per_texel_);
  for (int m = 0; m < cubemap.size(); ++m)
    for (int k = 0; k < per_texel_; ++k)
      texel_rays_[size_t(MortonSlot(0, m)) * per_texel_ + k] = pattern.Direction(m, k);
  edges_.resize(start_level_ + 1);
  anchors_.resize(start_level_ + 1);
  probe_direction_.resize(start_level_ + 1);
  for (int l = 0; l <= start_level_; ++l) {
    const Cubemap blocks(BlocksPerEdge(l));
    const int n = blocks.n();
    if (l > 0) {
      anchors_[l].resize(blocks.size());
      for (int b = 0; b < blocks.size(); ++b) {
        const Texel t = blocks.TexelOf(b);
        anchors_[l][b] = AnchorAt(l, t.face, t.x, t.y);
      }
      probe_direction_[l].resize(blocks.size());
      for (int b = 0; b < blocks.size(); ++b)
        probe_direction_[l][MortonSlot(l, b)] = pattern.Direction(Anchor(l, b), 0);
    }
    edges_[l].assign(size_t(6) * 4 * n * 8, -1);
    for (int b = 0; b < blocks.size(); ++b) {
      const Texel t = blocks.TexelOf(b);
      if (t.x > 0 && t.y > 0 && t.x < n - 1 && t.y < n - 1) continue;
      int32_t* out = &edges_[l][(size_t(t.face) * 4 * n + EdgeSlot(t.x, t.y, n)) * 8];
      for (int i = 0; i < 8; ++i)
        out[i] = Anchor(l, NeighbourOf(blocks, t.face, t.x + kOffsets[i][0], t.y + kOffsets[i][1]));
    }
  }
  start_blocks_.resize(BlockCount(start_level_));
  for (int b = 0; b < BlockCount(start_level_); ++b) start_blocks_[MortonSlot(start_level_, b)] = b;
  for (const Vec3& v : TexelIrradianceVectors(cubemap)) {
    phi_x_.push_back(v.x);
    phi_y_.push_back(v.y);
    phi_z_.push_back(v.z);
  }
  for (int f = 0; f < 6; ++f) {
    const auto p00 = Cubemap::FacePoint(f, 0, 0), p10 = Cubemap::FacePoint(f, 1, 0),
               p01 = Cubemap::FacePoint(f, 0, 1);
    for (int i = 0; i < 3; ++i) {
      frames_[f].origin[i] = p00[i];
      frames_[f].dx[i] = (p10[i] - p00[i]) / n_;
      frames_[f].dy[i] = (p01[i] - p00[i]) / n_;
    }
  }
}

}  // namespace wavebake
