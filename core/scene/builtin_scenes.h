#pragma once
// Scenes generated in code (DESIGN.md §5 `builtin:NAME`), for tests, demos
// and benchmarks without data files. Every one has Y up, a default camera,
// distinct albedos per mesh, and as meshes[0] a 64×64-vertex regular-grid
// ground (so the `grid` layout is a power-of-two image of it). The geometry
// constants are public so tests can compare against closed-form answers.
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"
#include "core/scene/scene.h"

namespace wavebake {

namespace builtin {

// Ground: vertex (i, j) at (kGroundMin + i*kGroundSpacing, y, kGroundMin +
// j*kGroundSpacing), so vertex (32, 32) sits exactly at the origin. The square
// is one cell short of symmetric; a centre vertex matters more (it is where
// the disk's analytic occlusion holds).
inline constexpr int kGroundVertices = 64;
inline constexpr float kGroundSpacing = 1.0f / 16;
inline constexpr float kGroundMin = -2.0f;
inline constexpr float kGroundMax = kGroundMin + (kGroundVertices - 1) * kGroundSpacing;
inline constexpr int kGroundCentreIndex = 32;  // grid vertex (32, 32) is the origin

// disk-over-plane: an opaque disk of radius r at height h above
// kDiskPlaneCentre, facing down. Seen from that ground point it blocks the
// cosine-weighted fraction r²/(r²+h²) of the upper hemisphere, so a diffuse
// receiver there keeps 1 − r²/(r²+h²) of a constant environment. The disk is
// a fan of kDiskSegments triangles with its rim on the circle, so its area is
// kDiskSegments/2 · r² · sin(2π/kDiskSegments), slightly below πr².
inline constexpr float kDiskRadius = 0.5f;
inline constexpr float kDiskHeight = 0.75f;
inline constexpr int kDiskSegments = 128;
inline constexpr Vec3 kDiskPlaneCentre{0, 0, 0};  // ground vertex (32, 32)

// cylinder-bump (Vollick & Lessig §6.1.1): a tall cylinder casting sharp
// shadows and a Gaussian bump y = A·exp(−d²/2σ²) raised out of the ground
// itself (the ground stays one height-field grid).
inline constexpr Vec3 kBumpCentre{0.7f, 0, 0.5f};
inline constexpr float kBumpHeight = 0.35f;
inline constexpr float kBumpSigma = 0.22f;
inline constexpr Vec3 kCylinderBase{-0.8f, 0, -0.5f};
inline constexpr float kCylinderRadius = 0.25f;
inline constexpr float kCylinderHeight = 1.6f;

// cubes-wall (§6.1.2): a 3×3 array of cubes standing on the ground, well in
// front of a wall along the ground's back edge (z = kGroundMin) facing +Z.
inline constexpr float kCubeSize = 0.4f;
inline constexpr float kCubeSpacing = 0.8f;  // centre to centre
inline constexpr float kWallHeight = 2.0f;

// sphere-plane: a sphere resting on the ground at the origin.
inline constexpr Vec3 kSphereCentre{0, 0.5f, 0};
inline constexpr float kSphereRadius = 0.5f;

}  // namespace builtin

// The scene called `name` (one of BuiltinSceneNames()); an error naming it
// otherwise. Pure computation: reads no files.
absl::StatusOr<Scene> MakeBuiltinScene(std::string_view name);

std::vector<std::string> BuiltinSceneNames();

}  // namespace wavebake
