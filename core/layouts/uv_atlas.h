#pragma once
// Where each mesh's UV atlas goes in a `uv` layout's lightmap (DESIGN.md §1
// "Spatial layout", §3 samples/uv_rects): the packing is part of the store's
// contract, so a runtime can find every mesh's texels from the store alone.
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"

namespace wavebake {

// The UV domain of one mesh: the unit square grown to the bounding box of
// its coordinates (atlases in the wild overhang [0, 1] by a little; spot.obj's
// u starts at −0.052). u0 < u1, v0 < v1 always.
struct UvDomain {
  float u0 = 0, v0 = 0, u1 = 1, v1 = 1;
};
UvDomain MeshUvDomain(std::span<const Vec2> uvs);

struct TexelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// The packing. One mesh: the whole W×H lightmap. Several: mesh i gets a
// square of side 2^k_i, first the largest power of two whose area is at most
// its share of the lightmap by surface area (at least 1), then — while the
// squares still fit — the side of the mesh furthest below its share
// (largest share/area ratio, ties: lower index) doubles. The squares are
// placed largest first (ties: lower index) along the Morton (Z) order of
// min(W,H)-sized square blocks laid along the long side, which packs power-of-two
// squares sorted by size without gaps. Error: more meshes than texels.
absl::StatusOr<std::vector<TexelRect>> PackCharts(std::span<const double> surface_areas, int width,
                                                  int height);

// Surface area of every mesh (world space).
std::vector<double> MeshAreas(const Scene& scene);

}  // namespace wavebake
