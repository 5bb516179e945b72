#pragma once
// The scene model: triangle meshes in world space with a diffuse albedo each,
// and an optional pinhole camera. Plain data; loaders (storage/scene_loader)
// and built-ins (core/builtin_scenes) fill it, transforms already applied.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/util/vec3.h"

namespace wavebake {

// A texture coordinate in assimp's (OpenGL) convention: v grows upwards,
// (0, 0) is the bottom-left corner of the image.
struct Vec2 {
  float u = 0, v = 0;
  constexpr bool operator==(const Vec2&) const = default;
};

struct Mesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // per vertex, unit length; same size as positions
  std::vector<std::array<uint32_t, 3>> triangles;
  // UV channels as the file has them ([channel][vertex], each the size of
  // positions): the `uv` layout reads channel 0, `uv1` channel 1. Empty when
  // the file has none; built-in shapes have none.
  std::vector<std::vector<Vec2>> uv_channels;
  Vec3 albedo{0.8f, 0.8f, 0.8f};  // diffuse RGB reflectance in [0,1]
  // A regular-grid mesh (the `grid` layout): vertex (i, j) = j * grid_width + i.
  int grid_width = 0, grid_height = 0;
};

struct Camera {
  Vec3 eye{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
  float fov_y_degrees = 45;
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::optional<Camera> camera;
};

}  // namespace wavebake
