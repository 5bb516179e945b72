#pragma once
// Move-only owners of Embree 3 handles: each releases its reference in its
// destructor, so no error path of RayCaster::Build can leak a device, a scene
// or a geometry.
#include <embree3/rtcore.h>

#include <memory>
#include <type_traits>

namespace wavebake::embree {

struct DeviceRelease {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneRelease {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
struct GeometryRelease {
  void operator()(RTCGeometry g) const { rtcReleaseGeometry(g); }
};

// RTCDevice etc. are pointers to opaque structs; unique_ptr owns the pointee type.
using Device = std::unique_ptr<std::remove_pointer_t<RTCDevice>, DeviceRelease>;
using SceneHandle = std::unique_ptr<std::remove_pointer_t<RTCScene>, SceneRelease>;
using Geometry = std::unique_ptr<std::remove_pointer_t<RTCGeometry>, GeometryRelease>;

}  // namespace wavebake::embree
