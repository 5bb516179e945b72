// RayCaster queries: single occlusion rays, fans of occlusion rays from one
// origin (packets or streams), and closest hits with surface attributes.
#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/transport/ray_caster.h"
#include "core/transport/ray_caster_state.h"

namespace wavebake {
namespace {

constexpr float kOccludedTfar = -std::numeric_limits<float>::infinity();  // Embree's "hit" mark
constexpr unsigned kAllMask = 0xFFFFFFFFu;  // Debian's Embree is built with ray masks on

RTCRay MakeRay(Vec3 origin, Vec3 dir, float tnear, float tfar) {
  RTCRay r;
  r.org_x = origin.x, r.org_y = origin.y, r.org_z = origin.z, r.tnear = tnear;
  r.dir_x = dir.x, r.dir_y = dir.y, r.dir_z = dir.z, r.time = 0;
  r.tfar = tfar, r.mask = kAllMask, r.id = 0, r.flags = 0;
  return r;
}

// Packets of W rays (RTCRay8 / RTCRay16 share their member names). The tail
// packet masks its unused lanes off through `valid`.
template <int W, typename Packet, auto kOccludedW>
void FanPackets(RTCScene scene, Vec3 o, const RayFan& fan, float tnear, float tfar,
                std::span<uint8_t> occluded) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one origin, neighbouring directions
  Packet p;
  alignas(64) int valid[W];
  for (int i = 0; i < W; ++i) {
    p.org_x[i] = o.x, p.org_y[i] = o.y, p.org_z[i] = o.z;
    p.time[i] = 0, p.mask[i] = kAllMask, p.id[i] = i, p.flags[i] = 0;
    p.tnear[i] = tnear;  // Embree writes only tfar back
    valid[i] = -1;
  }
  const size_t full = fan.size() / W * W;
  // Full packets: plain copies the compiler turns into vector moves.
  for (size_t base = 0; base < full; base += W) {
    for (int i = 0; i < W; ++i) {
      p.dir_x[i] = fan.x[base + i], p.dir_y[i] = fan.y[base + i], p.dir_z[i] = fan.z[base + i];
      p.tfar[i] = tfar;
    }
    kOccludedW(valid, scene, &ctx, &p);
    for (int i = 0; i < W; ++i) occluded[base + i] = p.tfar[i] == kOccludedTfar;
  }
  if (full == fan.size()) return;
  // The tail: unused lanes are masked off and repeat a valid ray.
  const int lanes = static_cast<int>(fan.size() - full);
  for (int i = 0; i < W; ++i) {
    const size_t j = full + std::min(i, lanes - 1);
    valid[i] = i < lanes ? -1 : 0;
    p.dir_x[i] = fan.x[j], p.dir_y[i] = fan.y[j], p.dir_z[i] = fan.z[j];
    p.tfar[i] = tfar;
  }
  kOccludedW(valid, scene, &ctx, &p);
  for (int i = 0; i < lanes; ++i) occluded[full + i] = p.tfar[i] == kOccludedTfar;
}

// Embree's stream interface: it regroups the rays into packets itself.
void FanStream(RTCScene scene, Vec3 o, const RayFan& fan, float tnear, float tfar,
               std::span<uint8_t> occluded) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  constexpr size_t kChunk = 64;
  RTCRay rays[kChunk];
  for (size_t base = 0; base < fan.size(); base += kChunk) {
    const size_t n = std::min(kChunk, fan.size() - base);
    for (size_t i = 0; i < n; ++i) {
      rays[i] = MakeRay(o, {fan.x[base + i], fan.y[base + i], fan.z[base + i]}, tnear, tfar);
    }
    rtcOccluded1M(scene, &ctx, rays, static_cast<unsigned>(n), sizeof(RTCRay));
    for (size_t i = 0; i < n; ++i) occluded[base + i] = rays[i].tfar == kOccludedTfar;
  }
}

void FanSingle(RTCScene scene, Vec3 o, const RayFan& fan, float tnear, float tfar,
               std::span<uint8_t> occluded) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (size_t i = 0; i < fan.size(); ++i) {
    RTCRay r = MakeRay(o, {fan.x[i], fan.y[i], fan.z[i]}, tnear, tfar);
    rtcOccluded1(scene, &ctx, &r);
    occluded[i] = r.tfar == kOccludedTfar;
  }
}

Vec3 Lerp3(Vec3 a, Vec3 b, Vec3 c, float u, float v) { return a * (1 - u - v) + b * u + c * v; }

uint32_t NearestCorner(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 d[3] = {p - a, p - b, p - c};
  uint32_t best = 0;
  for (uint32_t i = 1; i < 3; ++i) {
    if (Dot(d[i], d[i]) < Dot(d[best], d[best])) best = i;
  }
  return best;
}

Hit MakeHit(const RayCasterMesh& mesh, const RTCRayHit& rh) {
  const auto& tri = mesh.triangles[rh.hit.primID];
  const Vec3 p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  const float u = rh.hit.u, v = rh.hit.v;
  Hit hit;
  hit.t = rh.ray.tfar;
  hit.position = Lerp3(p0, p1, p2, u, v);
  hit.mesh = rh.hit.geomID;
  hit.triangle = rh.hit.primID;
  hit.vertex = mesh.first_vertex + tri[NearestCorner(hit.position, p0, p1, p2)];
  const Vec3 geometric = Cross(p1 - p0, p2 - p0);  // counter-clockwise front face
  Vec3 n = geometric;
  if (!mesh.normals.empty()) {
    n = Lerp3(mesh.normals[tri[0]], mesh.normals[tri[1]], mesh.normals[tri[2]], u, v);
    if (!(Dot(n, n) > 0)) n = geometric;  // opposing vertex normals cancel out
  }
  hit.normal = Normalize(n);
  return hit;
}

}  // namespace

bool RayCaster::Occluded(Vec3 origin, Vec3 dir, float tnear, float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r = MakeRay(origin, dir, tnear, tfar);
  rtcOccluded1(state_->scene.get(), &ctx, &r);
  return r.tfar == kOccludedTfar;
}

void RayCaster::OccludedFan(Vec3 origin, const RayFan& fan, float tnear, float tfar,
                            std::span<uint8_t> occluded, FanKernel kernel) const {
  RTCScene scene = state_->scene.get();
  occluded = occluded.first(fan.size());
  switch (kernel) {
    case FanKernel::kSingle:
      return FanSingle(scene, origin, fan, tnear, tfar, occluded);
    case FanKernel::kPacket8:
      return FanPackets<8, RTCRay8, rtcOccluded8>(scene, origin, fan, tnear, tfar, occluded);
    case FanKernel::kPacket16:
      return FanPackets<16, RTCRay16, rtcOccluded16>(scene, origin, fan, tnear, tfar, occluded);
    case FanKernel::kStream:
      return FanStream(scene, origin, fan, tnear, tfar, occluded);
  }
}

std::optional<Hit> RayCaster::FirstHit(Vec3 origin, Vec3 dir, float tnear, float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray = MakeRay(origin, Normalize(dir), tnear, tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(state_->scene.get(), &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return MakeHit(state_->meshes[rh.hit.geomID], rh);
}

}  // namespace wavebake
