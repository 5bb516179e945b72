// RayCaster construction: validate the Scene, hand every mesh to Embree as a
// triangle geometry over shared buffers, commit once.
#include "core/transport/ray_caster.h"

#include <limits>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/transport/ray_caster_state.h"

namespace wavebake {
namespace {

std::string MeshLabel(size_t index, const Mesh& mesh) {
  return absl::StrCat("mesh ", index, " ('", mesh.name, "')");
}

absl::Status ValidateMesh(size_t index, const Mesh& mesh) {
  const std::string label = MeshLabel(index, mesh);
  if (mesh.positions.empty() || mesh.triangles.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(label, " is empty: ", mesh.positions.size(),
                                                   " vertices, ", mesh.triangles.size(),
                                                   " triangles"));
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    return absl::InvalidArgumentError(absl::StrCat(
        label, " has ", mesh.normals.size(), " normals for ", mesh.positions.size(), " vertices"));
  }
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!IsFinite(mesh.positions[v])) {
      return absl::InvalidArgumentError(absl::StrCat(label, " vertex ", v, " is not finite"));
    }
    if (!mesh.normals.empty() && !IsFinite(mesh.normals[v])) {
      return absl::InvalidArgumentError(absl::StrCat(label, " normal ", v, " is not finite"));
    }
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (uint32_t v : mesh.triangles[t]) {
      if (v >= mesh.positions.size()) {
        return absl::InvalidArgumentError(absl::StrCat(
            label, " triangle ", t, " references vertex ", v, " of ", mesh.positions.size()));
      }
    }
  }
  return absl::OkStatus();
}

absl::Status ValidateScene(const Scene& scene) {
  if (scene.meshes.empty()) {
    return absl::InvalidArgumentError(absl::StrCat("scene '", scene.name, "' has no meshes"));
  }
  uint64_t vertices = 0;
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (absl::Status s = ValidateMesh(i, scene.meshes[i]); !s.ok()) return s;
    vertices += scene.meshes[i].positions.size();
  }
  // Hit::vertex is a uint32 global id.
  if (vertices > std::numeric_limits<uint32_t>::max()) {
    return absl::InvalidArgumentError(
        absl::StrCat("scene '", scene.name, "' has ", vertices, " vertices, more than 2^32-1"));
  }
  return absl::OkStatus();
}

absl::Status EmbreeStatus(RTCDevice device, const std::string& step) {
  const RTCError e = rtcGetDeviceError(device);
  if (e == RTC_ERROR_NONE) return absl::OkStatus();
  return absl::InternalError(
      absl::StrCat("embree failed to ", step, " (RTCError ", static_cast<int>(e), ")"));
}

RayCasterMesh CopyMesh(const Mesh& mesh, uint32_t first_vertex) {
  RayCasterMesh m;
  m.positions = mesh.positions;
  m.positions.push_back(Vec3{});  // padding for Embree's 16-byte vertex loads
  m.normals = mesh.normals;
  m.triangles = mesh.triangles;
  m.first_vertex = first_vertex;
  return m;
}

absl::Status AttachMesh(RTCDevice device, RTCScene scene, const RayCasterMesh& mesh, unsigned id) {
  embree::Geometry geom(rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE));
  if (!geom) return EmbreeStatus(device, "create a triangle geometry");
  // Vec3 and std::array<uint32_t, 3> are tightly packed 12-byte records,
  // exactly RTC_FORMAT_FLOAT3 / RTC_FORMAT_UINT3 with stride 12.
  static_assert(sizeof(Vec3) == 3 * sizeof(float));
  static_assert(sizeof(mesh.triangles[0]) == 3 * sizeof(uint32_t));
  rtcSetSharedGeometryBuffer(geom.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             mesh.positions.data(), 0, sizeof(Vec3), mesh.positions.size() - 1);
  rtcSetSharedGeometryBuffer(geom.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                             mesh.triangles.data(), 0, sizeof(mesh.triangles[0]),
                             mesh.triangles.size());
  rtcCommitGeometry(geom.get());
  rtcAttachGeometryByID(scene, geom.get(), id);  // the scene now holds its own reference
  return EmbreeStatus(device, absl::StrCat("attach mesh ", id));
}

Bounds VertexBounds(const std::vector<RayCasterMesh>& meshes) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  Bounds b{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  for (const RayCasterMesh& m : meshes) {
    for (size_t v = 0; v + 1 < m.positions.size(); ++v) {  // skip the padding element
      b.lower = Min(b.lower, m.positions[v]);
      b.upper = Max(b.upper, m.positions[v]);
    }
  }
  return b;
}

}  // namespace

absl::StatusOr<RayCaster> RayCaster::Build(const Scene& scene) {
  if (absl::Status s = ValidateScene(scene); !s.ok()) return s;

  auto state = std::make_unique<State>();
  state->device.reset(rtcNewDevice(nullptr));
  if (!state->device) return EmbreeStatus(nullptr, "create a device");
  RTCDevice device = state->device.get();

  uint32_t first_vertex = 0;
  for (const Mesh& mesh : scene.meshes) {
    state->meshes.push_back(CopyMesh(mesh, first_vertex));
    first_vertex += static_cast<uint32_t>(mesh.positions.size());
  }
  state->vertex_count = first_vertex;
  state->bounds = VertexBounds(state->meshes);

  state->scene.reset(rtcNewScene(device));
  if (!state->scene) return EmbreeStatus(device, "create a scene");
  RTCScene rtc_scene = state->scene.get();
  // Robust traversal: no rays slip through shared edges of the tessellated
  // occluders, which would show as speckles in a binary visibility column.
  rtcSetSceneFlags(rtc_scene, RTC_SCENE_FLAG_ROBUST);
  // Built once, queried for S×M×K rays: spend time on the best BVH.
  rtcSetSceneBuildQuality(rtc_scene, RTC_BUILD_QUALITY_HIGH);
  for (size_t i = 0; i < state->meshes.size(); ++i) {
    absl::Status s = AttachMesh(device, rtc_scene, state->meshes[i], static_cast<unsigned>(i));
    if (!s.ok()) return s;
  }
  rtcCommitScene(rtc_scene);
  if (absl::Status s = EmbreeStatus(device, "commit the scene"); !s.ok()) return s;
  return RayCaster(std::move(state));
}

RayCaster::RayCaster(std::unique_ptr<State> state) : state_(std::move(state)) {}
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;
RayCaster::~RayCaster() = default;

Bounds RayCaster::bounds() const { return state_->bounds; }

float RayCaster::Diagonal() const { return Length(state_->bounds.upper - state_->bounds.lower); }

uint32_t RayCaster::vertex_count() const { return state_->vertex_count; }

}  // namespace wavebake
