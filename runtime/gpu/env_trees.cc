#include "runtime/gpu/env_trees.h"

#include "core/products/haar_tree.h"
#include "runtime/gpu/tree_stream.h"

namespace wavebake {

EnvTrees BuildEnvTrees(const WaveletLights& lights) {
  EnvTrees e;
  const int n = lights.light_res;
  e.light_res = n;
  e.terms = static_cast<int>(lights.lights.size());
  const int per_face = n * n;
  // Dense per face: the few selected coefficients, zero elsewhere.
  std::vector<std::array<float, 3>> dense(6 * static_cast<size_t>(per_face), {0, 0, 0});
  std::vector<uint8_t> selected(dense.size(), 0);
  for (const WaveletLight& l : lights.lights) {
    dense[l.column] = l.weight;
    selected[l.column] = 1;
  }
  const int squares = n >= 2 ? haar::SquaresOf(n) : 0;
  for (int face = 0; face < 6; ++face) {
    const size_t base = size_t(face) * per_face;
    e.scaling[face] = dense[base];
    e.offset[face] = static_cast<int32_t>(e.records.size() / 12);
    if (squares == 0) continue;
    std::vector<uint8_t> significant(squares, 0);
    for (int l = 0; l < haar::LevelsOf(n); ++l)
      for (int sy = 0; sy < (1 << l); ++sy)
        for (int sx = 0; sx < (1 << l); ++sx)
          for (int t = 0; t < 3; ++t)
            significant[haar::SquareId(l, sx, sy)] |=
                selected[base + haar::FaceIndex(n, l, t, sx, sy)];
    for (const TreeNode& node : DepthFirstNodes(n, KeepLive(n, significant))) {
      float rec[12] = {};
      for (int t = 0; t < 3; ++t) {
        const auto& c = dense[base + haar::FaceIndex(n, node.level, t, node.sx, node.sy)];
        rec[4 * t] = c[0];
        rec[4 * t + 1] = c[1];
        rec[4 * t + 2] = c[2];
      }
      rec[3] = static_cast<float>(node.child_mask);
      rec[7] = static_cast<float>(1 + node.descendants);
      e.records.insert(e.records.end(), rec, rec + 12);
    }
    e.count[face] = static_cast<int32_t>(e.records.size() / 12) - e.offset[face];
  }
  return e;
}

nlohmann::json EnvTreesJson(const EnvTrees& e) {
  nlohmann::json faces = nlohmann::json::array();
  for (int f = 0; f < 6; ++f)
    faces.push_back({{"offset", e.offset[f]},
                     {"count", e.count[f]},
                     {"scaling", {e.scaling[f][0], e.scaling[f][1], e.scaling[f][2]}}});
  return {{"light_res", e.light_res}, {"terms", e.terms}, {"faces", faces}, {"records", e.records}};
}

}  // namespace wavebake
