#include "runtime/io/lightmap.h"

#include <cmath>

#include "absl/strings/str_cat.h"
#include "core/columns/uncovered_fill.h"

namespace wavebake {

std::vector<float> DilateGutters(const SampleSet& samples, std::span<const float> rgb, int gutter) {
  std::vector<float> out(rgb.begin(), rgb.end());
  const CellFiller dilate(UncoveredFill::kDilate, samples.grid, samples.width, samples.height,
                          gutter);
  dilate.Fill(out, 3);
  return out;
}

absl::StatusOr<std::vector<std::vector<Vec2>>> LightmapUvs(const Scene& scene,
                                                           const SampleSet& samples,
                                                           int uv_channel) {
  if (scene.meshes.size() != samples.uv_charts.size())
    return absl::FailedPreconditionError(
        absl::StrCat("scene: ", scene.meshes.size(), " meshes, the store has ",
                     samples.uv_charts.size(), " charts (samples/uv_rects)"));
  std::vector<std::vector<Vec2>> out;
  const double w = samples.width, h = samples.height;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    const UvChart& c = samples.uv_charts[i];
    if (static_cast<size_t>(uv_channel) >= m.uv_channels.size())
      return absl::FailedPreconditionError(
          absl::StrCat("scene: mesh '", m.name, "' has no UV channel ", uv_channel));
    std::vector<Vec2>& uv = out.emplace_back();
    for (Vec2 t : m.uv_channels[uv_channel]) {
      const double x = c.x + (double(t.u) - c.u0) / (double(c.u1) - c.u0) * c.width;
      const double y = c.y + (double(c.v1) - t.v) / (double(c.v1) - c.v0) * c.height;
      uv.push_back({float(x / w), float(1 - y / h)});
    }
  }
  return out;
}

}  // namespace wavebake
