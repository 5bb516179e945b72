#pragma once
// A planar, one-sided, textured rectangular area light at finite distance
// (Sun & Ramamoorthi 2009 §5): the input of `relight --area-light` and of
// `eval --reference --area-light`. The wavelet path (runtime/near_field/near_field.h)
// and the Monte-Carlo reference (runtime/reference/area_reference.h) share this
// description and nothing else.
//
// The light lies in the plane p·major = height of a store's plane light
// domain (core/directions/light_domain.h: for the default axis +Y the plane y = height,
// in-plane coordinates (x, z)) and emits towards −major: points with
// p·major < height see its front, the others nothing. Its radiance is the
// same in every direction (§5.2.2) and varies over the rectangle:
//
//   L(u, v) = radiance × texture pixel (⌊u·W⌋, ⌊v·H⌋)   (piecewise constant)
//
// with (u, v) ∈ [0, 1]² across the rectangle: u along its first edge (the
// plane's s axis rotated by `rotation_degrees` towards its t axis), v along
// the second; texture row 0 at v = 0. No texture: the constant `radiance`.
//
// LIGHT.json holds one light object or an array of them:
//   {"centre": [s, t],          // in-plane coordinates (x, z for +Y); required
//    "height": 1.5,             // position of the plane along the axis; required
//    "size": [w, d],            // edge lengths, > 0; required
//    "rotation_degrees": 0,     // about the axis, from s towards t
//    "radiance": [r, g, b],     // ≥ 0; the colour, or the texture's multiplier (default 1)
//    "texture": "light.png",    // EXR, Radiance HDR or PNG (sRGB, linearized);
//                               // relative to the JSON file
//    "resolution": 32}          // R: the wavelet path's source image, power of two 2..256
// Unknown keys are errors; messages name the file and the field.
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/util/vec3.h"
#include "runtime/env/env_map.h"

namespace wavebake {

struct AreaLight {
  std::array<double, 2> centre{0, 0};
  double height = 1;
  std::array<double, 2> size{1, 1};
  double rotation_degrees = 0;
  Vec3 radiance{1, 1, 1};
  EnvMap texture;            // width 0: none
  std::string texture_path;  // as resolved, for messages
  int resolution = 32;
};

// Reads LIGHT.json (one light or an array). Errors name the file and field.
absl::StatusOr<std::vector<AreaLight>> LoadAreaLights(const std::filesystem::path& path);
// One light object; `where` prefixes messages, textures resolve against `dir`.
absl::StatusOr<AreaLight> ParseAreaLight(const nlohmann::json& j, const std::string& where,
                                         const std::filesystem::path& dir);

// A light moving and resizing over frames (`relight --area-light-sequence`):
// SEQ.json = {"frames": F, "from": LIGHT, "to": LIGHT}; frame f of F is the
// linear interpolation at f/(F−1) of centre, height, size, rotation and
// radiance; texture and resolution come from "from" ("to" may omit them and
// any other field it keeps).
struct AreaLightSequence {
  int frames = 0;
  AreaLight from, to;
  AreaLight Frame(int f) const;
};
absl::StatusOr<AreaLightSequence> LoadAreaLightSequence(const std::filesystem::path& path);

}  // namespace wavebake
