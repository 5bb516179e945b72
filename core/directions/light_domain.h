#pragma once
// The directions a row of T spans (DESIGN.md §1 "Directions"): the six faces
// of the cubemap, or — for near-field planar lights — one expanded face of
// size S aligned with the light plane (Sun & Ramamoorthi 2009 §5.2.1). The
// standard cube face has size 2 (it spans [−1, 1]² at unit distance); a face
// of size S spans [−S/2, S/2]² and covers more of the hemisphere above the
// light plane (S = 10: 82 % of its solid angle, 99 % of a centred cosine
// lobe), at the price of coarser texels in the middle. N×N texels, light
// index m = y·N + x, texel centres at (i+0.5)/N, the orientation of the cube
// face the plane is aligned with (OpenGL cubemap convention), exact solid
// angles by the same corner formula as the cube's.
#include <string>
#include <string_view>

#include "absl/status/statusor.h"
#include "core/directions/cubemap.h"
#include "core/util/vec3.h"

namespace wavebake {

struct LightDomain {
  enum class Kind { kCube, kPlane };
  Kind kind = Kind::kCube;
  double size = 2;   // plane: face edge S at unit distance, in [kMinPlaneSize, kMaxPlaneSize]
  int axis = kPosY;  // plane: the CubeFace whose axis is the plane's normal
  static constexpr double kMinPlaneSize = 3, kMaxPlaneSize = 10;

  bool is_plane() const { return kind == Kind::kPlane; }
  int faces() const { return is_plane() ? 1 : 6; }
  // M, the number of light directions (columns of T) at N texels per edge.
  int Columns(int n) const { return faces() * n * n; }
  bool operator==(const LightDomain&) const = default;
};

// "cube" | "plane:S" (axis +Y) | "plane:S:AXIS", AXIS one of +X −X +Y −Y +Z −Z
// (an ASCII '-' also reads as −). ToString gives the canonical spelling,
// which ParseLightDomain reads back to the same value (the axis is omitted
// when it is +Y). Errors name the `light_domain` field.
std::string ToString(const LightDomain& d);
absl::StatusOr<LightDomain> ParseLightDomain(std::string_view spec);
// Range and axis checks (ParseLightDomain applies them too).
absl::Status ValidateLightDomain(const LightDomain& d);

// The orientation of a cube face (OpenGL table 3.21): the unnormalized
// direction through face coordinates (sc, tc) ∈ [−1, 1]² is major + sc·s_axis
// + tc·t_axis. For +Y: major +Y, s_axis +X, t_axis +Z.
struct FaceFrame {
  Vec3 major, s_axis, t_axis;
};
FaceFrame FaceFrameOf(int face);

// The expanded face of a plane light domain: its texels, directions and
// solid angles. A point's coordinates in the light plane are (p·s_axis,
// p·t_axis) and its height p·major; the direction through face coordinates
// (s, t) ∈ [0,1]² is major + S(s−½)·s_axis + S(t−½)·t_axis, so from a point
// at distance z below the plane it meets the plane at in-plane offset
// z·S·(s−½, t−½): the affine map of Eq. 29 with scale z·S.
class PlaneFace {
 public:
  PlaneFace(int n, double size, int axis);
  explicit PlaneFace(int n, const LightDomain& d) : PlaneFace(n, d.size, d.axis) {}

  int n() const { return n_; }
  double size() const { return size_; }
  int axis() const { return axis_; }
  const FaceFrame& frame() const { return frame_; }
  int texels() const { return n_ * n_; }

  // Unit direction through face coordinates (s, t) ∈ [0,1]².
  Vec3 Direction(double s, double t) const;
  Vec3 TexelCenter(int m) const;
  // Exact solid angle of texel m (corner formula on the face at unit distance).
  double SolidAngle(int m) const;
  // Solid angle of the whole face: 4·atan((S/2)² / sqrt(S²/2 + 1)); 4π/6 for S = 2.
  double TotalSolidAngle() const;
  // Texel whose square contains direction d, or −1 if d does not pass
  // through the face (points away from the plane or outside [−S/2, S/2]²).
  int Lookup(Vec3 d) const;

 private:
  int n_;
  double size_;
  int axis_;
  FaceFrame frame_;
};

}  // namespace wavebake
