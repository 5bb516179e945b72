#include "core/scene/builtin_scenes.h"

#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "core/scene/builtin_shapes.h"

namespace wavebake {
namespace {

using namespace builtin;

// Grey (Mesh's default albedo), unlike every object placed on it.
Mesh FlatGround() {
  return MakeHeightField("ground", kGroundVertices, kGroundMin, kGroundMin, kGroundSpacing,
                         [](float, float) { return 0.0f; });
}

Mesh NamedMesh(std::string name, Vec3 albedo) {
  Mesh m;
  m.name = std::move(name);
  m.albedo = albedo;
  return m;
}

Scene Furnace() {
  Scene s{.name = "furnace", .meshes = {FlatGround()}, .camera = {}};
  // Albedo 1: with L ≡ 1 and nothing occluding, the relit result is exactly 1.
  s.meshes[0].albedo = {1, 1, 1};
  s.camera = Camera{.eye = {0, 3.0f, 4.0f}, .target = {0, 0, 0}};
  return s;
}

Scene DiskOverPlane() {
  Scene s{.name = "disk-over-plane", .meshes = {FlatGround()}, .camera = {}};
  Mesh disk = NamedMesh("disk", {0.8f, 0.3f, 0.2f});
  const Vec3 centre = kDiskPlaneCentre + Vec3{0, kDiskHeight, 0};
  AppendFan(disk, {centre, {0, -1, 0}},
            AppendCircle(disk, centre, kDiskRadius, kDiskSegments, {0, -1, 0}));
  s.meshes.push_back(std::move(disk));
  s.camera = Camera{.eye = {0, 2.2f, 3.6f}, .target = {0, 0.3f, 0}};
  return s;
}

Scene CylinderBump() {
  Mesh ground = MakeHeightField(
      "ground", kGroundVertices, kGroundMin, kGroundMin, kGroundSpacing, [](float x, float z) {
        const float dx = x - kBumpCentre.x, dz = z - kBumpCentre.z;
        return kBumpHeight * std::exp(-(dx * dx + dz * dz) / (2 * kBumpSigma * kBumpSigma));
      });
  Scene s{.name = "cylinder-bump", .meshes = {std::move(ground)}, .camera = {}};
  Mesh cylinder = NamedMesh("cylinder", {0.25f, 0.45f, 0.8f});
  AppendCylinder(cylinder, kCylinderBase, kCylinderRadius, kCylinderHeight, 48, 17);
  s.meshes.push_back(std::move(cylinder));
  s.camera = Camera{.eye = {0.4f, 2.8f, 4.4f}, .target = {0, 0.5f, 0}};
  return s;
}

Scene CubesWall() {
  Scene s{.name = "cubes-wall", .meshes = {FlatGround()}, .camera = {}};
  Mesh wall = NamedMesh("wall", {0.55f, 0.75f, 0.55f});
  // V = +X, U = +Y: the patch winding (∂j × ∂i) then faces +Z, towards the cubes.
  const int rows = 33;
  AppendPatch(wall, rows, kGroundVertices, false, [&](int i, int j) {
    const float y = kWallHeight * static_cast<float>(i) / static_cast<float>(rows - 1);
    const float x = kGroundMin + static_cast<float>(j) * kGroundSpacing;
    return SurfacePoint{{x, y, kGroundMin}, {0, 0, 1}};
  });
  Mesh cubes = NamedMesh("cubes", {0.85f, 0.6f, 0.2f});
  const Vec3 half{kCubeSize / 2, 0, kCubeSize / 2};
  for (int a = -1; a <= 1; ++a) {
    for (int b = -1; b <= 1; ++b) {
      const Vec3 foot{static_cast<float>(a) * kCubeSpacing, 0,
                      static_cast<float>(b) * kCubeSpacing};
      AppendOpenBox(cubes, foot - half, foot + half + Vec3{0, kCubeSize, 0}, 8);
    }
  }
  s.meshes.push_back(std::move(wall));
  s.meshes.push_back(std::move(cubes));
  s.camera = Camera{.eye = {0, 2.6f, 4.2f}, .target = {0, 0.5f, -0.4f}};
  return s;
}

Scene SpherePlane() {
  Scene s{.name = "sphere-plane", .meshes = {FlatGround()}, .camera = {}};
  Mesh sphere = NamedMesh("sphere", {0.8f, 0.25f, 0.25f});
  AppendSphere(sphere, kSphereCentre, kSphereRadius, 64, 31);
  s.meshes.push_back(std::move(sphere));
  s.camera = Camera{.eye = {0, 2.0f, 3.2f}, .target = {0, 0.35f, 0}};
  return s;
}

struct SceneEntry {
  const char* name;
  Scene (*make)();
};
constexpr SceneEntry kScenes[] = {{"furnace", Furnace},
                                  {"disk-over-plane", DiskOverPlane},
                                  {"cylinder-bump", CylinderBump},
                                  {"cubes-wall", CubesWall},
                                  {"sphere-plane", SpherePlane}};

}  // namespace

absl::StatusOr<Scene> MakeBuiltinScene(std::string_view name) {
  for (const SceneEntry& e : kScenes) {
    if (name == e.name) {
      return e.make();
    }
  }
  return absl::InvalidArgumentError(
      absl::StrCat("scene: unknown built-in 'builtin:", std::string(name),
                   "' (known: ", absl::StrJoin(BuiltinSceneNames(), ", "), ")"));
}

std::vector<std::string> BuiltinSceneNames() {
  std::vector<std::string> names;
  for (const SceneEntry& e : kScenes) names.emplace_back(e.name);
  return names;
}

}  // namespace wavebake
