#pragma once
// The lighting side of Boulton §4.5's double product on a GPU: the n-term
// lighting approximation (runtime/relight/lighting.h SelectWaveletLights — the same
// terms the CPU relighter uses) as one pruned Haar tree per cube face, RGB
// per coefficient, in the depth-first line with jump records of
// runtime/gpu/tree_stream.h. A node is significant when one of its three
// wavelets is a selected light; the four children of a node go together, so
// the shader's parallel walk of a transfer tree and an environment tree
// visits only their intersection (Eq. 3). A few KB per frame of lighting.
#include <array>
#include <cstdint>
#include <vector>

#include "nlohmann/json.hpp"
#include "runtime/relight/lighting.h"

namespace wavebake {

struct EnvTrees {
  int light_res = 0;
  int terms = 0;  // selected lights
  // 3 RGBA float texels a record. Node: (c0.rgb, level+1 of the next node
  // or 0), (c1.rgb, 0), (c2.rgb, 0). Jump (after a node whose children
  // follow): (records from the node to the one past its subtree, level+1 of
  // that record or 0, 0, 0), then two zero texels.
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
