#pragma once
// Ray queries against a static Scene, backed by one committed Embree 3 scene.
// Built once, read-only afterwards: every const method is safe to call from
// many threads at once (Embree allows concurrent queries on a committed
// scene; each call keeps its own intersection context on the stack).
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"
#include "core/util/vec3.h"

namespace wavebake {

struct Hit {
  float t = 0;        // distance along the (unit) ray direction
  Vec3 position;      // on the triangle (barycentric interpolation of its vertices)
  Vec3 normal;        // unit; interpolated vertex normal, or geometric if the mesh has none
  uint32_t mesh = 0;  // index into Scene::meshes
  uint32_t triangle = 0;
  uint32_t vertex = 0;  // nearest vertex of the hit triangle, global id (meshes in order)
};

struct Bounds {
  Vec3 lower, upper;
};

// Many directions from one origin, struct-of-arrays (all three the same size).
struct RayFan {
  std::span<const float> x, y, z;
  size_t size() const { return x.size(); }
};

// How OccludedFan hands rays to Embree. All give identical answers; they
// differ only in speed (bench/transport.cc measures them).
enum class FanKernel { kSingle, kPacket8, kPacket16, kStream };

class RayCaster {
 public:
  // Fails with InvalidArgument naming the mesh (and vertex/triangle) for an
  // empty scene or mesh, non-finite vertices, out-of-range indices, or a
  // normals array whose size differs from positions.
  static absl::StatusOr<RayCaster> Build(const Scene& scene);

  // Move-only; a moved-from RayCaster may only be assigned to or destroyed.
  RayCaster(RayCaster&&) noexcept;
  RayCaster& operator=(RayCaster&&) noexcept;
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;
  ~RayCaster();

  // True if any triangle is hit with t in [tnear, tfar]. dir need not be unit
  // (t is then measured in units of |dir|).
  bool Occluded(Vec3 origin, Vec3 dir, float tnear, float tfar) const;

  // occluded[i] = Occluded(origin, fan[i], tnear, tfar) as 0/1, for all rays of
  // the fan at once (packets or a stream: the transport row's hot loop).
  // occluded.size() must be at least fan.size().
  void OccludedFan(Vec3 origin, const RayFan& fan, float tnear, float tfar,
                   std::span<uint8_t> occluded, FanKernel kernel = kDefaultFanKernel) const;
  static constexpr FanKernel kDefaultFanKernel = FanKernel::kPacket16;

  // Closest hit along origin + t·dir, t in [tnear, tfar]; dir is normalized here.
  std::optional<Hit> FirstHit(Vec3 origin, Vec3 dir, float tnear = 0,
                              float tfar = std::numeric_limits<float>::infinity()) const;

  // Axis-aligned box of all vertices (exact, not Embree's padded bounds).
  Bounds bounds() const;
  float Diagonal() const;
  // DESIGN.md §1: rays start at x + ε n with ε scaling with the scene.
  float DefaultEpsilon() const { return 1e-4f * Diagonal(); }

  uint32_t vertex_count() const;  // total over meshes, the range of Hit::vertex

 private:
  struct State;
  explicit RayCaster(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace wavebake
