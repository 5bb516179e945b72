#pragma once
// Spatial layouts (DESIGN.md §1 "Spatial layout"): where each spatial sample
// sits on the W×H grid whose column images the column transform compresses.
// This file: the `layout` spec and the two mesh layouts; the camera layout
// (ray casting) lives elsewhere.
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"

namespace wavebake {

enum class LayoutKind { kCamera, kGrid, kHilbert, kUv };

// What the column stage puts in the cells no sample covers before the column
// transform (core/columns/uncovered_fill.h). They decode to values nobody reads (the
// runtime masks them), so the fill only decides how many coefficients the
// chart borders cost. Only the uv layout fills; every other layout keeps zeros.
enum class UncoveredFill { kZero, kPushPull, kDilate };

struct LayoutSpec {
  LayoutKind kind = LayoutKind::kCamera;
  // Powers of two in 1..4096. For kGrid both are 0: the grid mesh decides.
  int width = 64, height = 64;
  // kUv only: the UV channel (0 = `uv`, 1 = `uv1`), whether texels inside
  // several triangles are allowed, and the uncovered-cell fill.
  int uv_channel = 0;
  bool allow_uv_overlap = false;
  UncoveredFill fill = UncoveredFill::kZero;
};

// The uv layout's fill unless the spec names one (docs/RESULTS.md chart 7).
inline constexpr UncoveredFill kDefaultUvFill = UncoveredFill::kPushPull;

// `camera` (= camera:64x64) | `camera:WxH` | `grid` | `hilbert:WxH` |
// `uv[1][:WxH][,allow-overlap][,fill=zero|push-pull|dilate]` (uv = uv:256x256).
// Errors name the `layout` field and say what is wrong.
absl::StatusOr<LayoutSpec> ParseLayout(std::string_view spec);
// The canonical spelling, which ParseLayout reads back: "camera:64x64", "grid",
// "hilbert:128x64", "uv1:512x512,allow-overlap" (the fill only when it is not
// kDefaultUvFill).
std::string ToString(const LayoutSpec& spec);
std::string_view ToString(UncoveredFill fill);

// `--allow-uv-overlap`: the canonical spelling of `layout` with
// allow_uv_overlap set. Error (naming allow-uv-overlap): not a uv layout.
absl::StatusOr<std::string> WithUvOverlapAllowed(std::string_view layout);

// Vertex (i, j) of the scene's first regular-grid mesh is cell (x=i, y=j) and
// sample id y*W + x; W×H are the mesh's grid dims (powers of two ≤ 4096). No
// cell is masked. `vertex` holds global vertex ids: all meshes' vertices
// numbered in mesh order. The scene must have passed CheckAndRepairScene.
absl::StatusOr<SampleSet> GridLayout(const Scene& scene);

// Every vertex of every mesh is a sample, and sample id = global vertex id.
// Vertices are ordered by a 3D Hilbert key of their position (quantized in the
// scene's bounding cube; ties by id) and placed in that order along a 2D
// Hilbert curve through the W×H grid, so neighbours in space tend to be
// neighbours on the grid; the curve's tail stays masked (−1). For W ≠ H the
// curve runs through consecutive min(W,H)-square blocks along the long side
// (see HilbertCurveCells). Error if there are more vertices than cells.
absl::StatusOr<SampleSet> HilbertLayout(const Scene& scene, int width, int height);

// One sample per lightmap texel that a mesh's UV atlas covers (channel
// spec.uv_channel): every mesh gets its rectangle of the W×H lightmap
// (core/layouts/uv_atlas.h PackCharts) and its UV domain fills it. Triangles are
// rasterized conservatively — a texel any triangle's interior touches is
// covered, so charts thinner than a texel keep their texels — and the texel's
// sample is the point of its nearest triangle closest to the texel centre
// (the centre itself when inside), with position, normal and albedo
// interpolated barycentrically there. Sample ids follow the meshes in order,
// and each mesh's texels row by row within its rectangle. Errors name the mesh: no such UV channel
// (suggesting hilbert), overlapping UVs (texel centres inside two triangles; the fraction is given)
// unless spec.allow_uv_overlap, no texel covered.
absl::StatusOr<SampleSet> UvLayout(const Scene& scene, const LayoutSpec& spec);

}  // namespace wavebake
