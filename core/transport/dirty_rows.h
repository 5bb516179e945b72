#pragma once
// Which rows of T an edit of the scene can change, decided without tracing
// the scene (Boulton §4.5: only the transfer functions the change reaches).
//
// A row is a function of (sample, ε, the rays of the shared jitter pattern,
// and each ray's visibility): both brute force and refinement only ever
// trace rays of that pattern (core/transport/refined_row.h: a probe is ray 0
// of its anchor texel) and decide the rest from their answers. A ray's
// visibility is occluded(static) ∨ occluded(changed) with static the meshes
// the edit left alone: it can differ between the old and the new scene only
// if the ray hits the changed geometry (old or new placement) and misses the
// static one. So a sample none of whose 6N²K pattern rays both hits the
// changed triangles and escapes the static ones has the same row, bit for bit.
//
// The test is cheap because most rays never reach a changed triangle: per
// sample and per changed mesh a bounding cone (the mesh's bounding sphere
// seen from the ray origin) is intersected with each texel's cone (its
// centre and the angle to its farthest corner: every jittered direction of
// the texel is inside it), and only the rays of texels whose cones meet are
// traced, first against a BVH of the changed triangles alone and, for the
// few that hit, against the static meshes.
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/directions/jitter_pattern.h"
#include "core/scene/scene.h"
#include "core/scene/scene_check.h"
#include "core/transport/ray_caster.h"
#include "core/util/vec3.h"

namespace wavebake {

struct DirtyRowOptions {
  // Also ask whether a changed ray is blocked by the unchanged meshes (then
  // its visibility is 0 in both scenes). Off: every ray that reaches the
  // changed triangles marks its row, a coarser but still conservative test.
  bool static_occlusion = true;
};

// Counters over the samples tested (progress and the store's update record).
struct DirtyRowStats {
  uint64_t texels_in_cones = 0;  // texels whose cone meets a changed bound
  uint64_t rays_changed = 0;     // rays traced against the changed triangles
  uint64_t rays_static = 0;      // of those that hit, rays traced against the static meshes
};

class DirtyRowTest {
 public:
  // changed: the removed and added meshes (core/scene/scene_diff.h
  // ChangedGeometry), at least one; unchanged: the others (may be empty).
  // The pattern is the bake's (cube light domain).
  static absl::StatusOr<DirtyRowTest> Build(const Scene& changed, const Scene& unchanged,
                                            const JitterPattern& pattern,
                                            const DirtyRowOptions& options = {});

  // Whether the row of the sample at (position, normal) with ray offset
  // epsilon may differ between the scenes (false: it is the same bits).
  // Thread-safe; stats may be null.
  bool MayChange(Vec3 position, Vec3 normal, float epsilon, DirtyRowStats* stats) const;

  // How many texels' cones meet a changed bound seen from the sample's ray
  // origin (RowDelta traces their rays): the cost of a patch.
  int TexelsInCones(Vec3 position, Vec3 normal, float epsilon) const;

  // For `--update`'s row patch: the old placement (removed meshes) and the
  // new one (added meshes) as separate scenes, so RowDelta can tell which
  // one a ray hits. Either may be empty.
  absl::Status SetPlacements(const Scene& removed, const Scene& added);
  // delta (M values, overwritten) = the brute-force transport row of the new
  // scene minus the old one's, in the pixel basis, over the rays of the
  // texels whose cones meet a changed bound (every other ray has the same
  // visibility in both): Ω_m/(Kπ) Σ_{n·ω_k>0} (V_new,k − V_old,k) n·ω_k,
  // the brute-force entry of DESIGN.md §1. Returns whether any entry is
  // non-zero. Needs SetPlacements; thread-safe.
  bool RowDelta(Vec3 position, Vec3 normal, float epsilon, std::span<float> delta,
                DirtyRowStats* stats) const;

 private:
  struct Sphere {
    Vec3 centre;
    float radius;
  };
  DirtyRowTest(RayCaster changed, std::optional<RayCaster> unchanged, JitterPattern pattern,
               DirtyRowOptions options);
  bool TexelRaysChange(Vec3 origin, int m, DirtyRowStats& stats) const;
  // f(m) for every texel whose cone meets a changed bound seen from origin,
  // until f returns true; whether it did.
  template <class F>
  bool ForTexelsInCones(Vec3 origin, DirtyRowStats& stats, F f) const;

  std::shared_ptr<const RayCaster> changed_;
  std::shared_ptr<const RayCaster> unchanged_;        // null: nothing left to occlude
  std::shared_ptr<const RayCaster> removed_, added_;  // SetPlacements; null: none
  std::shared_ptr<const JitterPattern> pattern_;
  DirtyRowOptions options_;
  std::vector<Sphere> bounds_;  // one per changed mesh
  std::vector<Bounds3> boxes_;  // the same meshes' boxes, padded: rays missing all skip Embree
  bool MissesBoxes(Vec3 origin, Vec3 dir) const;
  // Per texel: unit centre direction, cos and sin of its angular radius.
  std::vector<Vec3> centre_;
  std::vector<float> cos_radius_, sin_radius_;
  // Square blocks of up to 8×8 texels of one face, each with a cone holding
  // its texels' cones: a block whose cone misses a changed bound skips its
  // texels' tests (most of a row's 6N² texels are far from a small edit).
  struct TexelBlock {
    Vec3 centre{0, 0, 1};
    float cos_radius = 0, sin_radius = 1;
    bool wide = true;  // radius ≥ 90°: never skipped (the cosine test needs α + β < 180°)
    int first = 0, count = 0;  // its texels: block_texels_[first, first + count)
  };
  std::vector<TexelBlock> blocks_;
  std::vector<int> block_texels_;
  void BuildBlocks(const std::vector<float>& radius);
};

}  // namespace wavebake
