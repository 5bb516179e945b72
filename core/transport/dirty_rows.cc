#include "core/transport/dirty_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "core/scene/scene_check.h"

namespace wavebake {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// Slack on every angle and radius, far above float rounding of the cone
// test: a margin costs a few extra traced rays, never a missed one.
constexpr float kAnglePad = 1e-4f;
constexpr float kRadiusPad = 1e-4f;

Bounds3 MeshBounds(const Mesh& m) {
  Bounds3 b;
  for (Vec3 p : m.positions) {
    b.lo = Min(b.lo, p);
    b.hi = Max(b.hi, p);
  }
  return b;
}

}  // namespace

DirtyRowTest::DirtyRowTest(RayCaster changed, std::optional<RayCaster> unchanged,
                           JitterPattern pattern, DirtyRowOptions options)
    : changed_(std::make_shared<RayCaster>(std::move(changed))),
      unchanged_(unchanged ? std::make_shared<RayCaster>(*std::move(unchanged)) : nullptr),
      pattern_(std::make_shared<JitterPattern>(std::move(pattern))),
      options_(options) {}

absl::StatusOr<DirtyRowTest> DirtyRowTest::Build(const Scene& changed, const Scene& unchanged,
                                                 const JitterPattern& pattern,
                                                 const DirtyRowOptions& options) {
  if (changed.meshes.empty())
    return absl::InvalidArgumentError("changed: no changed mesh (nothing can be dirty)");
  if (pattern.corners.size() != static_cast<size_t>(pattern.texels()) * 4)
    return absl::InvalidArgumentError("pattern: needs the corners of every texel (cube domain)");
  absl::StatusOr<RayCaster> changed_caster = RayCaster::Build(changed);
  if (!changed_caster.ok()) return changed_caster.status();
  std::optional<RayCaster> unchanged_caster;
  if (!unchanged.meshes.empty()) {
    absl::StatusOr<RayCaster> c = RayCaster::Build(unchanged);
    if (!c.ok()) return c.status();
    unchanged_caster.emplace(*std::move(c));
  }
  DirtyRowTest test(*std::move(changed_caster), std::move(unchanged_caster), pattern, options);
  for (const Mesh& m : changed.meshes) {
    const Bounds3 b = MeshBounds(m);
    const float r = 0.5f * b.diagonal();
    test.bounds_.push_back({b.centre(), r * (1 + kRadiusPad) + 1e-6f});
    const Vec3 pad = Vec3{1, 1, 1} * (r * kRadiusPad + 1e-6f);
    test.boxes_.push_back({b.lo - pad, b.hi + pad});
  }
  const int texels = pattern.texels();
  if (texels != 6 * pattern.n * pattern.n)
    return absl::InvalidArgumentError(
        absl::StrCat("pattern: ", texels, " texels, not 6·", pattern.n, "² (cube domain)"));
  std::vector<float> radii(texels);
  test.centre_.resize(texels);
  test.cos_radius_.resize(texels);
  test.sin_radius_.resize(texels);
  for (int m = 0; m < texels; ++m) {
    const Vec3* c = &pattern.corners[static_cast<size_t>(m) * 4];
    const Vec3 centre = Normalize(c[0] + c[1] + c[2] + c[3]);
    // A texel is the conic hull of its corners (a convex spherical
    // quadrilateral under 90°), so its farthest point from the centre is a corner.
    float radius = 0;
    for (int k = 0; k < 4; ++k)
      radius = std::max(radius, std::acos(std::clamp(Dot(centre, c[k]), -1.0f, 1.0f)));
    radius += kAnglePad;
    radii[m] = radius;
    test.centre_[m] = centre;
    test.cos_radius_[m] = std::cos(radius);
    test.sin_radius_[m] = std::sin(radius);
  }
  test.BuildBlocks(radii);
  return test;
}

void DirtyRowTest::BuildBlocks(const std::vector<float>& radius) {
  const int n = pattern_->n, b = std::min(8, n);
  for (int face = 0; face < 6; ++face)
    for (int y0 = 0; y0 < n; y0 += b)
      for (int x0 = 0; x0 < n; x0 += b) {
        TexelBlock block;
        block.first = static_cast<int>(block_texels_.size());
        Vec3 sum{0, 0, 0};
        for (int y = y0; y < std::min(y0 + b, n); ++y)
          for (int x = x0; x < std::min(x0 + b, n); ++x) {
            const int m = (face * n + y) * n + x;
            block_texels_.push_back(m);
            sum = sum + centre_[m];
          }
        block.count = static_cast<int>(block_texels_.size()) - block.first;
        block.centre = Normalize(sum);
        // Every texel cone inside: the farthest texel centre plus its radius.
        float r = 0;
        for (int i = block.first; i < block.first + block.count; ++i) {
          const int m = block_texels_[i];
          const float to_texel = std::acos(std::clamp(Dot(block.centre, centre_[m]), -1.0f, 1.0f));
          r = std::max(r, to_texel + radius[m]);
        }
        r += kAnglePad;
        block.wide = r >= std::numbers::pi_v<float> / 2;
        block.cos_radius = std::cos(r);
        block.sin_radius = std::sin(r);
        blocks_.push_back(block);
      }
}

// Slab test of the ray origin + t·dir, t ≥ 0, against every padded box: a
// ray that misses them all cannot hit a changed triangle.
bool DirtyRowTest::MissesBoxes(Vec3 origin, Vec3 dir) const {
  for (const Bounds3& b : boxes_) {
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    bool hit = true;
    for (int a = 0; a < 3 && hit; ++a) {
      const double o = origin[a], d = dir[a], lo = b.lo[a], hi = b.hi[a];
      if (d == 0) {
        hit = o >= lo && o <= hi;
        continue;
      }
      double ta = (lo - o) / d, tb = (hi - o) / d;
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      hit = t0 <= t1;
    }
    if (hit) return false;
  }
  return true;
}

bool DirtyRowTest::TexelRaysChange(Vec3 origin, int m, DirtyRowStats& stats) const {
  for (int k = 0; k < pattern_->per_texel; ++k) {
    const Vec3 dir = pattern_->Direction(m, k);
    if (MissesBoxes(origin, dir)) continue;
    ++stats.rays_changed;
    if (!changed_->Occluded(origin, dir, 0, kInf)) continue;
    if (!options_.static_occlusion || !unchanged_) return true;
    ++stats.rays_static;
    if (!unchanged_->Occluded(origin, dir, 0, kInf)) return true;
  }
  return false;
}

template <class F>
bool DirtyRowTest::ForTexelsInCones(Vec3 origin, DirtyRowStats& stats, F f) const {
  bool dirty = false;
  // A texel in two cones is visited once; only the entries set are cleared.
  thread_local std::vector<uint8_t> seen;
  thread_local std::vector<int> visited;
  const bool dedupe = bounds_.size() > 1;
  if (dedupe && seen.size() != static_cast<size_t>(pattern_->texels()))
    seen.assign(pattern_->texels(), 0);
  visited.clear();
  for (const Sphere& s : bounds_) {
    const Vec3 to = s.centre - origin;
    const float d = Length(to);
    const bool inside = d <= s.radius;
    // The sphere seen from the origin: a cone of half-angle α about `axis`.
    const Vec3 axis = inside ? Vec3{0, 0, 1} : to / d;
    const float sin_a = inside ? 1 : s.radius / d;
    const float cos_a = std::sqrt(std::max(0.0f, 1 - sin_a * sin_a));
    // The cones meet iff angle(centre, axis) ≤ α + β; α < 90° and β < 90°,
    // so α + β < 180° where cos is decreasing: compare cosines,
    // cos(α + β) = cos α cos β − sin α sin β.
    auto misses = [&](Vec3 centre, float cos_b, float sin_b) {
      return !inside && Dot(centre, axis) < cos_a * cos_b - sin_a * sin_b;
    };
    for (const TexelBlock& b : blocks_) {
      if (dirty) break;
      if (!b.wide && misses(b.centre, b.cos_radius, b.sin_radius)) continue;
      for (int i = b.first; i < b.first + b.count && !dirty; ++i) {
        const int m = block_texels_[i];
        if (misses(centre_[m], cos_radius_[m], sin_radius_[m])) continue;
        if (dedupe) {
          if (seen[m]) continue;
          seen[m] = 1;
          visited.push_back(m);
        }
        ++stats.texels_in_cones;
        dirty = f(m);
      }
    }
    if (dirty) break;
  }
  for (int m : visited) seen[m] = 0;
  return dirty;
}

int DirtyRowTest::TexelsInCones(Vec3 position, Vec3 normal, float epsilon) const {
  DirtyRowStats stats;
  ForTexelsInCones(position + normal * epsilon, stats, [](int) { return false; });
  return static_cast<int>(stats.texels_in_cones);
}

absl::Status DirtyRowTest::SetPlacements(const Scene& removed, const Scene& added) {
  for (auto [scene, caster] : {std::pair{&removed, &removed_}, std::pair{&added, &added_}}) {
    if (scene->meshes.empty()) {
      caster->reset();
      continue;
    }
    absl::StatusOr<RayCaster> c = RayCaster::Build(*scene);
    if (!c.ok()) return c.status();
    *caster = std::make_shared<RayCaster>(*std::move(c));
  }
  return absl::OkStatus();
}

bool DirtyRowTest::RowDelta(Vec3 position, Vec3 normal, float epsilon, std::span<float> delta,
                            DirtyRowStats* stats) const {
  DirtyRowStats local;
  const Vec3 origin = position + normal * epsilon;
  std::fill(delta.begin(), delta.end(), 0.0f);
  bool any = false;
  const int per = pattern_->per_texel;
  ForTexelsInCones(origin, local, [&](int m) {
    float sum = 0;
    for (int k = 0; k < per; ++k) {
      const Vec3 dir = pattern_->Direction(m, k);
      const float c = Dot(normal, dir);
      if (c <= 0 || MissesBoxes(origin, dir)) continue;
      ++local.rays_changed;
      // No trace of the union first: nearly every ray that meets a box hits
      // that placement (the cubes-wall-like bench edit: 1 443 165 of
      // 1 443 709), so it would only add a traversal.
      const bool was = removed_ && removed_->Occluded(origin, dir, 0, kInf);
      const bool is = added_ && added_->Occluded(origin, dir, 0, kInf);
      if (was == is) continue;
      ++local.rays_static;
      if (unchanged_ && unchanged_->Occluded(origin, dir, 0, kInf)) continue;
      sum += (was ? 1.0f : -1.0f) * c;  // V_new − V_old: visible where the old placement was
    }
    if (sum != 0) {
      delta[m] = pattern_->solid_angle[m] / (per * std::numbers::pi_v<float>)*sum;
      any = true;
    }
    return false;
  });
  if (stats) {
    stats->texels_in_cones += local.texels_in_cones;
    stats->rays_changed += local.rays_changed;
    stats->rays_static += local.rays_static;
  }
  return any;
}

bool DirtyRowTest::MayChange(Vec3 position, Vec3 normal, float epsilon,
                             DirtyRowStats* stats) const {
  DirtyRowStats local;
  const Vec3 origin = position + normal * epsilon;  // as the bake's rays (DESIGN.md §1)
  const bool dirty =
      ForTexelsInCones(origin, local, [&](int m) { return TexelRaysChange(origin, m, local); });
  if (stats) {
    stats->texels_in_cones += local.texels_in_cones;
    stats->rays_changed += local.rays_changed;
    stats->rays_static += local.rays_static;
  }
  return dirty;
}

}  // namespace wavebake
