#include "runtime/reference/path_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "absl/strings/str_cat.h"

namespace wavebake {

struct PathScene::State {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  const Scene* source = nullptr;
  ~State() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

PathScene::PathScene(std::unique_ptr<State> state, float offset)
    : state_(std::move(state)), offset_(offset) {}
PathScene::PathScene(PathScene&&) noexcept = default;
PathScene& PathScene::operator=(PathScene&&) noexcept = default;
PathScene::~PathScene() = default;

absl::StatusOr<PathScene> PathScene::Build(const Scene& scene) {
  auto state = std::make_unique<State>();
  state->source = &scene;
  state->device = rtcNewDevice(nullptr);
  if (!state->device) return absl::InternalError("path reference: no Embree device");
  state->scene = rtcNewScene(state->device);
  rtcSetSceneBuildQuality(state->scene, RTC_BUILD_QUALITY_HIGH);
  Vec3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
          std::numeric_limits<float>::max()};
  Vec3 hi{-lo.x, -lo.y, -lo.z};
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    RTCGeometry g = rtcNewGeometry(state->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                             mesh.triangles.size()));
    if (!v || !t) {
      rtcReleaseGeometry(g);
      return absl::InternalError(absl::StrCat("path reference: mesh '", mesh.name, "' buffers"));
    }
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3 p = mesh.positions[i];
      v[3 * i] = p.x, v[3 * i + 1] = p.y, v[3 * i + 2] = p.z;
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) t[3 * i + k] = mesh.triangles[i][k];
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(state->scene, g, static_cast<unsigned>(m));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(state->scene);
  const Vec3 d = hi - lo;
  const float diagonal = scene.meshes.empty() ? 1.0f : std::sqrt(Dot(d, d));
  return PathScene(std::move(state), 1e-4f * diagonal);
}

namespace {

RTCRayHit PathRay(Vec3 o, Vec3 d) {
  RTCRayHit rh;
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = 0, rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.time = 0, rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
  rh.hit.geomID = rh.hit.primID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

std::optional<PathHit> PathScene::Trace(Vec3 origin, Vec3 dir) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = PathRay(origin, dir);
  rtcIntersect1(state_->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  const Mesh& mesh = state_->source->meshes[rh.hit.geomID];
  const std::array<uint32_t, 3>& tri = mesh.triangles[rh.hit.primID];
  // Embree's barycentrics: p = (1 − u − v) p0 + u p1 + v p2.
  const float u = rh.hit.u, v = rh.hit.v, w = 1 - u - v;
  const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  PathHit hit;
  hit.mesh = rh.hit.geomID;
  hit.position = origin + dir * rh.ray.tfar;
  Vec3 n = Cross(p1 - p0, p2 - p0);
  if (mesh.normals.size() == mesh.positions.size()) {
    const Vec3 s = mesh.normals[tri[0]] * w + mesh.normals[tri[1]] * u + mesh.normals[tri[2]] * v;
    if (Dot(s, s) > 0) n = s;
  }
  hit.normal = Normalize(n);
  // A sample's front is the side its normal points to (DESIGN.md §1), so a
  // surface's front is the side of its shading normal, whatever the winding.
  hit.front = Dot(hit.normal, dir) < 0;
  return hit;
}

bool PathScene::Blocked(Vec3 origin, Vec3 dir) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = PathRay(origin, dir);
  rtcOccluded1(state_->scene, &ctx, &rh.ray);
  return rh.ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace wavebake
