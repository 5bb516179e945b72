#pragma once
// The lighting side of Boulton §4.5's double product on a GPU: the n-term
// lighting approximation (runtime/relight/lighting.h SelectWaveletLights — the same
// terms the CPU relighter uses) as one pruned Haar tree per cube face, RGB
// per coefficient, depth first as in runtime/gpu/tree_stream.h. A node is
// kept when one of its three wavelets, or one of a descendant's, is a
// selected light; each node records its child mask and its subtree's size,
// so the shader's parallel walk of a transfer tree and an environment tree
// visits only their intersection (Eq. 3) and skips an environment branch
// in one step. A few KB per frame of lighting.
#include <array>
#include <cstdint>
#include <vector>

#include "nlohmann/json.hpp"
#include "runtime/relight/lighting.h"

namespace wavebake {

struct EnvTrees {
  int light_res = 0;
  int terms = 0;  // selected lights
  // 3 RGBA float texels a node, depth first: (c0.rgb, child mask: bit k =
  // child k follows), (c1.rgb, nodes in its subtree, itself included),
  // (c2.rgb, 0).
  std::vector<float> records;
  std::array<int32_t, 6> offset{}, count{};  // per face, in records
  std::array<std::array<float, 3>, 6> scaling{};
};

// lights: column ids of a light_res cube (Haar rows), RGB weights.
EnvTrees BuildEnvTrees(const WaveletLights& lights);

// {"light_res", "terms", "faces": [{"offset", "count", "scaling": [r,g,b]}],
//  "records": [floats]}: what the viewer uploads.
nlohmann::json EnvTreesJson(const EnvTrees& e);

}  // namespace wavebake
