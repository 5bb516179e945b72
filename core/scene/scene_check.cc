#include "core/scene/scene_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace wavebake {
namespace {

std::string Label(const Mesh& m, size_t index) {
  return absl::StrCat("mesh '", m.name, "' (#", index, ")");
}

std::string Show(Vec3 v) { return absl::StrFormat("(%g, %g, %g)", v.x, v.y, v.z); }

absl::Status Invalid(const std::string& where, const std::string& what) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", what));
}

struct DVec {
  double x = 0, y = 0, z = 0;
};
DVec ToD(Vec3 v) { return {v.x, v.y, v.z}; }
DVec SubD(DVec a, DVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DVec CrossD(DVec a, DVec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double Norm2(DVec a) { return a.x * a.x + a.y * a.y + a.z * a.z; }

// Twice the area vector of a triangle, in double so that rounding of float
// positions does not make a sliver look degenerate or vice versa.
DVec AreaVector(const Mesh& m, const std::array<uint32_t, 3>& t) {
  const DVec a = ToD(m.positions[t[0]]);
  return CrossD(SubD(ToD(m.positions[t[1]]), a), SubD(ToD(m.positions[t[2]]), a));
}

// Zero area up to double rounding relative to the triangle's size: such a
// triangle has no normal and no visibility footprint.
bool IsDegenerate(const Mesh& m, const std::array<uint32_t, 3>& t) {
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
  const DVec a = ToD(m.positions[t[0]]), b = ToD(m.positions[t[1]]), c = ToD(m.positions[t[2]]);
  const double longest = std::max({Norm2(SubD(b, a)), Norm2(SubD(c, b)), Norm2(SubD(a, c))});
  const double twice_area = std::sqrt(Norm2(AreaVector(m, t)));
  return twice_area <= 1e-10 * longest;
}

absl::Status CheckVertices(const Mesh& m, const std::string& where) {
  if (m.positions.empty()) return Invalid(where, "has no vertices");
  if (m.triangles.empty()) return Invalid(where, "has no triangles");
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (!IsFinite(m.positions[i]))
      return Invalid(where, absl::StrCat("vertex ", i, " is not finite ", Show(m.positions[i])));
  if (!m.normals.empty() && m.normals.size() != m.positions.size())
    return Invalid(
        where, absl::StrCat(m.normals.size(), " normals for ", m.positions.size(), " vertices"));
  for (size_t c = 0; c < m.uv_channels.size(); ++c) {
    const std::vector<Vec2>& uv = m.uv_channels[c];
    if (uv.size() != m.positions.size())
      return Invalid(where, absl::StrCat("UV channel ", c, " has ", uv.size(), " coordinates for ",
                                         m.positions.size(), " vertices"));
    for (size_t i = 0; i < uv.size(); ++i)
      if (!std::isfinite(uv[i].u) || !std::isfinite(uv[i].v))
        return Invalid(where, absl::StrCat("UV channel ", c, ": vertex ", i, " has a non-finite (",
                                           uv[i].u, ", ", uv[i].v, ")"));
  }
  if (m.grid_width != 0 || m.grid_height != 0) {
    if (m.grid_width <= 0 || m.grid_height <= 0 ||
        int64_t{m.grid_width} * m.grid_height != static_cast<int64_t>(m.positions.size()))
      return Invalid(where, absl::StrCat("grid ", m.grid_width, "x", m.grid_height,
                                         " does not match ", m.positions.size(), " vertices"));
  }
  const Vec3 a = m.albedo;
  if (!IsFinite(a) || a.x < 0 || a.y < 0 || a.z < 0 || a.x > 1 || a.y > 1 || a.z > 1)
    return Invalid(where, absl::StrCat("albedo ", Show(a), " is outside [0, 1]"));
  return absl::OkStatus();
}

// Drops degenerate triangles; an index out of range is an error, not a repair:
// it means the file is corrupt, not merely sloppy.
absl::StatusOr<int> DropDegenerate(Mesh& m, const std::string& where) {
  const size_t n = m.positions.size();
  std::vector<std::array<uint32_t, 3>> kept;
  kept.reserve(m.triangles.size());
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    for (uint32_t v : t)
      if (v >= n)
        return Invalid(where, absl::StrCat("triangle ", i, " has vertex index ", v,
                                           " out of range (", n, " vertices)"));
    if (!IsDegenerate(m, t)) kept.push_back(t);
  }
  const int dropped = static_cast<int>(m.triangles.size() - kept.size());
  m.triangles = std::move(kept);
  if (m.triangles.empty()) return Invalid(where, "has no non-degenerate triangles");
  return dropped;
}

// Area-weighted: the unnormalized face cross product is twice the area times
// the face normal, so summing it weighs big faces more than slivers.
std::vector<Vec3> SmoothNormals(const Mesh& m, int* isolated) {
  std::vector<DVec> sum(m.positions.size());
  for (const auto& t : m.triangles) {
    const DVec a = AreaVector(m, t);
    for (uint32_t v : t) sum[v] = {sum[v].x + a.x, sum[v].y + a.y, sum[v].z + a.z};
  }
  std::vector<Vec3> normals(sum.size());
  for (size_t i = 0; i < sum.size(); ++i) {
    const double len = std::sqrt(Norm2(sum[i]));
    if (len > 0 && std::isfinite(len)) {
      normals[i] = {static_cast<float>(sum[i].x / len), static_cast<float>(sum[i].y / len),
                    static_cast<float>(sum[i].z / len)};
    } else {
      normals[i] = {0, 1, 0};  // isolated vertex (or faces that cancel): any unit vector will do
      ++*isolated;
    }
  }
  return normals;
}

// Keeps good given normals (normalized); replaces missing or unusable ones
// by smooth normals. Returns how many were computed.
int RepairNormals(Mesh& m, int* isolated) {
  std::vector<Vec3> smooth;
  int computed = 0;
  if (m.normals.empty()) m.normals.assign(m.positions.size(), Vec3{});
  for (size_t i = 0; i < m.normals.size(); ++i) {
    const float len = Length(m.normals[i]);
    if (std::isfinite(len) && len > 1e-20f) {
      m.normals[i] = m.normals[i] / len;
      continue;
    }
    if (smooth.empty()) smooth = SmoothNormals(m, isolated);
    m.normals[i] = smooth[i];
    ++computed;
  }
  return computed;
}

absl::Status CheckCamera(const Camera& c) {
  if (!IsFinite(c.eye) || !IsFinite(c.target) || !IsFinite(c.up))
    return Invalid("camera", "eye, target and up must be finite");
  if (c.eye == c.target) return Invalid("camera", "eye equals target");
  if (Length(Cross(c.target - c.eye, c.up)) == 0)
    return Invalid("camera.up", "is zero or parallel to the viewing direction");
  if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180))
    return Invalid("camera.fov_y_degrees", absl::StrCat(c.fov_y_degrees, " is outside (0, 180)"));
  return absl::OkStatus();
}

}  // namespace

absl::Status CheckAndRepairScene(Scene& scene, SceneReport* report) {
  SceneReport local;
  SceneReport& r = report ? *report : local;
  if (scene.meshes.empty())
    return Invalid(absl::StrCat("scene '", scene.name, "'"), "has no meshes");
  int64_t total = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    Mesh& m = scene.meshes[i];
    const std::string where = Label(m, i);
    if (absl::Status s = CheckVertices(m, where); !s.ok()) return s;
    total += static_cast<int64_t>(m.positions.size());
    // Sample and vertex ids are int32 throughout the store.
    if (total > INT32_MAX) return Invalid(where, "the scene has more than 2^31 - 1 vertices");
    absl::StatusOr<int> dropped = DropDegenerate(m, where);
    if (!dropped.ok()) return dropped.status();
    int isolated = 0;
    const int computed = RepairNormals(m, &isolated);
    r.dropped_triangles += *dropped;
    r.computed_normals += computed;
    r.isolated_vertices += isolated;
    if (*dropped > 0)
      r.warnings.push_back(absl::StrCat(where, ": dropped ", *dropped, " degenerate triangles"));
    if (isolated > 0)
      r.warnings.push_back(
          absl::StrCat(where, ": ", isolated, " vertices are in no triangle (normal set to +Y)"));
  }
  if (scene.camera) return CheckCamera(*scene.camera);
  return absl::OkStatus();
}

Bounds3 SceneBounds(const Scene& scene) {
  Bounds3 b;
  for (const Mesh& m : scene.meshes)
    for (Vec3 p : m.positions) {
      b.lo = Min(b.lo, p);
      b.hi = Max(b.hi, p);
    }
  return b;
}

}  // namespace wavebake
