#pragma once
// The outputs of relighting a `uv` store (DESIGN.md §5 relight): the
// lightmap itself, with its charts dilated into gutters so that bilinear
// (and mip-mapped) sampling near a chart border does not read the
// background, and a glTF 2.0 of the baked meshes that carries the lightmap
// UVs and the lightmap as its texture, so that any glTF viewer shows the
// relit result.
#include <cstddef>
#include <filesystem>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"

namespace wavebake {

// Texels of gutter around every chart: enough for bilinear sampling at the
// full resolution and two mip levels below it.
inline constexpr int kLightmapGutter = 4;

// rgb [W*H*3] as relit (NaN where no sample) with every uncovered texel
// within `gutter` texels (Chebyshev) of a chart set to a nearest chart
// texel's value (core/columns/uncovered_fill.h kDilate); texels farther away stay NaN.
std::vector<float> DilateGutters(const SampleSet& samples, std::span<const float> rgb,
                                 int gutter = kLightmapGutter);

// The lightmap UV of every vertex of every mesh, in the convention of the
// whole W×H lightmap (v up, as assimp holds it): each mesh's UV channel
// mapped through its chart (samples.uv_charts, mesh order). Error: the
// scene's meshes do not match the charts (count, UV channel).
absl::StatusOr<std::vector<std::vector<Vec2>>> LightmapUvs(const Scene& scene,
                                                           const SampleSet& samples,
                                                           int uv_channel);

// A glTF 2.0 (.gltf with its .bin beside it, or one .glb, by out's
// extension) written by assimp's exporter: one mesh per scene mesh with
// positions, normals and the lightmap UVs (LightmapUvs) as TEXCOORD_0, and
// one material that emits the lightmap: black base colour, `png` (embedded)
// as emissive texture with emissive factor 1, sampled with clamp-to-edge —
// the texture already holds the outgoing radiance. Atomic: all files appear
// at once or none.
absl::Status WriteLightmapGltf(const std::filesystem::path& out, const Scene& scene,
                               const std::vector<std::vector<Vec2>>& lightmap_uvs,
                               std::span<const std::byte> png);

}  // namespace wavebake
