// The `uv` layout: lightmap texels of the meshes' UV atlases.
#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/layouts/layout.h"
#include "core/layouts/uv_atlas.h"
#include "core/layouts/uv_raster.h"

namespace wavebake {
namespace {

// A texel centre this deep inside two triangles (in texels) is an overlap;
// less is float noise of charts that share an edge.
constexpr double kOverlapMargin = 1e-4;

// The best triangle found so far for each texel of the lightmap.
// Floats: 24 bytes a texel, so even a 4096² lightmap's picks fit in memory.
struct TexelPick {
  float distance2 = std::numeric_limits<float>::infinity();
  int32_t triangle = -1;
  std::array<float, 3> bary{};
  uint8_t inside = 0;  // triangles whose interior holds the centre (saturating)
};

// Texel coordinates of every vertex: the domain fills the rectangle, v up
// in the UVs and row 0 at the top of the lightmap.
std::vector<P2> TexelCoordinates(std::span<const Vec2> uvs, const UvDomain& d, const TexelRect& r) {
  std::vector<P2> out;
  out.reserve(uvs.size());
  const double su = r.width / (double(d.u1) - d.u0), sv = r.height / (double(d.v1) - d.v0);
  for (Vec2 t : uvs)
    out.push_back({r.x + (double(t.u) - d.u0) * su, r.y + (d.v1 - double(t.v)) * sv});
  return out;
}

void RasterizeMesh(const Mesh& m, const std::vector<P2>& texel_xy, const TexelRect& r, int width,
                   std::vector<TexelPick>& picks) {
  for (size_t k = 0; k < m.triangles.size(); ++k) {
    const auto& t = m.triangles[k];
    const std::array<P2, 3> tri{texel_xy[t[0]], texel_xy[t[1]], texel_xy[t[2]]};
    const double lo_x = std::min({tri[0].x, tri[1].x, tri[2].x});
    const double hi_x = std::max({tri[0].x, tri[1].x, tri[2].x});
    const double lo_y = std::min({tri[0].y, tri[1].y, tri[2].y});
    const double hi_y = std::max({tri[0].y, tri[1].y, tri[2].y});
    const int x0 = std::max(r.x, int(std::floor(lo_x))),
              x1 = std::min(r.x + r.width, int(std::ceil(hi_x)));
    const int y0 = std::max(r.y, int(std::floor(lo_y))),
              y1 = std::min(r.y + r.height, int(std::ceil(hi_y)));
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        if (!CoversTexel(tri, x, y)) continue;
        TexelPick& pick = picks[size_t(y) * width + x];
        const P2 centre{x + 0.5, y + 0.5};
        if (InsideBy(tri, centre, kOverlapMargin) && pick.inside < 255) ++pick.inside;
        const NearestPoint q = NearestOnTriangle(tri, centre);
        if (float(q.distance2) < pick.distance2)
          pick = {float(q.distance2),
                  int32_t(k),
                  {float(q.bary[0]), float(q.bary[1]), float(q.bary[2])},
                  pick.inside};
      }
    }
  }
}

template <class T>
T Interpolate(const std::vector<T>& v, const std::array<uint32_t, 3>& t,
              const std::array<float, 3>& b) {
  return v[t[0]] * b[0] + v[t[1]] * b[1] + v[t[2]] * b[2];
}

// Appends the samples of the texels in `r` (row-major) and returns how many
// of them lie inside two or more triangles.
int64_t EmitSamples(const Mesh& m, const TexelRect& r, const std::vector<TexelPick>& picks,
                    SampleSet& s) {
  int64_t overlapping = 0;
  for (int y = r.y; y < r.y + r.height; ++y) {
    for (int x = r.x; x < r.x + r.width; ++x) {
      const size_t cell = size_t(y) * s.width + x;
      const TexelPick& p = picks[cell];
      if (p.triangle < 0) continue;
      overlapping += p.inside >= 2;
      const auto& t = m.triangles[p.triangle];
      Vec3 n = Interpolate(m.normals, t, p.bary);
      if (!(Length(n) > 0))
        n = Cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
      s.grid[cell] = s.size();
      s.position.push_back(Interpolate(m.positions, t, p.bary));
      s.normal.push_back(Normalize(n));
      s.albedo.push_back(m.albedo);
    }
  }
  return overlapping;
}

}  // namespace

absl::StatusOr<SampleSet> UvLayout(const Scene& scene, const LayoutSpec& spec) {
  const std::string name = absl::StrCat("layout '", ToString(spec), "'");
  const int channel = spec.uv_channel;
  for (const Mesh& m : scene.meshes) {
    if (static_cast<size_t>(channel) >= m.uv_channels.size())
      return absl::InvalidArgumentError(
          absl::StrCat(name, ": mesh '", m.name, "' has no UV channel ", channel, " (it has ",
                       m.uv_channels.size(),
                       "); give it a lightmap atlas or bake it with --layout hilbert:WxH"));
    if (m.normals.size() != m.positions.size())
      return absl::FailedPreconditionError(absl::StrCat(
          name, ": mesh '", m.name, "' has not been through CheckAndRepairScene (no normals)"));
  }
  absl::StatusOr<std::vector<TexelRect>> rects =
      PackCharts(MeshAreas(scene), spec.width, spec.height);
  if (!rects.ok()) return rects.status();
  SampleSet s;
  s.width = spec.width;
  s.height = spec.height;
  s.grid.assign(size_t(s.width) * s.height, -1);
  // Each mesh has its own rectangle, so one pass per mesh over the shared picks.
  std::vector<TexelPick> picks(s.grid.size());
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    const TexelRect& r = (*rects)[i];
    const UvDomain d = MeshUvDomain(m.uv_channels[channel]);
    RasterizeMesh(m, TexelCoordinates(m.uv_channels[channel], d, r), r, s.width, picks);
    const int first = s.size();
    const int64_t overlapping = EmitSamples(m, r, picks, s);
    const int covered = s.size() - first;
    if (covered == 0)
      return absl::InvalidArgumentError(absl::StrCat(
          name, ": mesh '", m.name, "' covers no texel of its ", r.width, "x", r.height,
          " rectangle (UV channel ", channel, " has no triangle of positive area)"));
    if (overlapping > 0 && !spec.allow_uv_overlap)
      return absl::InvalidArgumentError(absl::StrFormat(
          "%s: mesh '%s' has overlapping UVs in channel %d: %.2f %% of its %d texels (%d) lie "
          "inside two or more triangles; a lightmap needs one surface point per texel (use uv1 "
          "if the second channel is the lightmap atlas, or --allow-uv-overlap)",
          name, m.name, channel, 100.0 * double(overlapping) / covered, covered, overlapping));
    s.uv_charts.push_back({m.name, r.x, r.y, r.width, r.height, d.u0, d.v0, d.u1, d.v1});
  }
  return s;
}

}  // namespace wavebake
