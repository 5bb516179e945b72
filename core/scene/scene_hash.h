#pragma once
// Content hash of a scene: the key under which workers cache scenes and the
// `scene hash` a store records (DESIGN.md §3, §4). It covers what a bake
// sees — positions, normals, triangles, albedo, grid dims, camera — and not
// names or where the scene came from, so two loads of the same content agree.
#include <string>

#include "core/scene/scene.h"

namespace wavebake {

// uv_channel ≥ 0 also covers that UV channel of every mesh: the hash of a
// `uv`/`uv1` bake, whose samples the UVs decide (other layouts ignore UVs and
// keep the hash they always had).
//
// 128 bits as 32 lowercase hex digits. Stable across runs, builds and
// platforms: it hashes a canonical little-endian serialization (floats by
// their IEEE-754 bits, −0 as +0), never memory layout.
std::string SceneHash(const Scene& scene, int uv_channel = -1);

}  // namespace wavebake
