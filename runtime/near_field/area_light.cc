#include "runtime/near_field/area_light.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "runtime/io/image_io.h"
#include "storage/files/json_file.h"

namespace wavebake {
namespace {

using nlohmann::json;

absl::Status Bad(const std::string& where, const std::string& field, const auto&... why) {
  return absl::InvalidArgumentError(absl::StrCat(where, ": ", field, ": ", why...));
}

absl::StatusOr<double> Number(const json& j, const std::string& where, const std::string& field) {
  if (!j.is_number()) return Bad(where, field, "expected a number, got ", j.dump());
  const double v = j.get<double>();
  if (!std::isfinite(v)) return Bad(where, field, "is not finite");
  return v;
}

template <size_t K>
absl::StatusOr<std::array<double, K>> Numbers(const json& j, const std::string& where,
                                              const std::string& field) {
  if (!j.is_array() || j.size() != K)
    return Bad(where, field, "expected an array of ", K, " numbers, got ", j.dump());
  std::array<double, K> out{};
  for (size_t i = 0; i < K; ++i) {
    absl::StatusOr<double> v = Number(j[i], where, absl::StrCat(field, "[", i, "]"));
    if (!v.ok()) return v.status();
    out[i] = *v;
  }
  return out;
}

std::string AsciiLowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

absl::Status CheckTexture(const std::string& where, const EnvMap& t) {
  for (float v : t.rgb)
    if (!(std::isfinite(v) && v >= 0))
      return Bad(where, "texture", "radiance must be finite and non-negative (found ", v, ")");
  return absl::OkStatus();
}

// A length (centre, height, size) the float geometry can square: the
// reference samples the light in float world coordinates, and |d|² of a
// point 1e19 away already overflows (FLT_MAX 3.4e38). A size of 1e308 made
// the light's bounding box infinite and the light vanish, rc 0.
absl::Status CheckLength(const std::string& where, const std::string& field, double v) {
  if (std::fabs(v) <= kMaxAreaLightLength) return absl::OkStatus();
  return Bad(where, field, v, " is beyond ±", kMaxAreaLightLength,
             " scene units (float geometry would overflow)");
}

// The brightest texel times `radiance` within the environment's bound
// (kMaxEnvRadiance, runtime/env/env_map.h): the same single-precision sums carry
// it. float(1e39) is inf, and 3e38 overflowed the relighting.
absl::Status CheckEmitted(const std::string& where, const AreaLight& l) {
  float texel = 1;
  if (l.texture.width > 0) texel = *std::max_element(l.texture.rgb.begin(), l.texture.rgb.end());
  for (int c = 0; c < 3; ++c) {
    const double emitted = double(l.radiance[c]) * texel;
    if (emitted <= kMaxEnvRadiance) continue;
    return Bad(where, l.texture.width > 0 ? "radiance × texture" : "radiance", "channel ",
               std::string(1, "RGB"[c]), " emits ", emitted, ", above ", kMaxEnvRadiance,
               " (the relighting's float sums would overflow; scale it down)");
  }
  return absl::OkStatus();
}

absl::StatusOr<EnvMap> LoadTexture(const std::filesystem::path& path, const std::string& where) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return Bad(where, "texture", "no such file '", path.string(), "'");
  const std::string ext = AsciiLowercase(path.extension().string());
  absl::StatusOr<EnvMap> image =
      ext == ".exr"   ? ReadExrImage(path)
      : ext == ".hdr" ? ReadHdrImage(path)
      : ext == ".png" ? ReadPngImage(path)
                      : absl::StatusOr<EnvMap>(Bad(where, "texture", "unknown format '", ext,
                                                   "' (.exr, .hdr or .png)"));
  if (!image.ok()) return image.status();
  if (absl::Status s = CheckTexture(where, *image); !s.ok()) return s;
  return image;
}

constexpr const char* kKeys[] = {"centre",   "height",  "size",      "rotation_degrees",
                                 "radiance", "texture", "resolution"};

}  // namespace

absl::StatusOr<AreaLight> ParseAreaLight(const json& j, const std::string& where,
                                         const std::filesystem::path& dir) {
  if (!j.is_object()) return Bad(where, "light", "expected an object, got ", j.dump());
  for (const auto& item : j.items()) {
    const std::string& key = item.key();  // a structured binding clang 14 cannot capture
    if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key == k; }) ==
        std::end(kKeys))
      return Bad(where, key, "unknown key (allowed: ", absl::StrJoin(kKeys, ", "), ")");
  }
  for (const char* required : {"centre", "height", "size"})
    if (!j.contains(required)) return Bad(where, required, "missing");
  AreaLight l;
  absl::StatusOr<std::array<double, 2>> centre = Numbers<2>(j["centre"], where, "centre");
  if (!centre.ok()) return centre.status();
  l.centre = *centre;
  absl::StatusOr<double> height = Number(j["height"], where, "height");
  if (!height.ok()) return height.status();
  l.height = *height;
  absl::StatusOr<std::array<double, 2>> size = Numbers<2>(j["size"], where, "size");
  if (!size.ok()) return size.status();
  if (!((*size)[0] > 0 && (*size)[1] > 0)) return Bad(where, "size", "edges must be > 0");
  l.size = *size;
  for (int i = 0; i < 2; ++i) {
    if (absl::Status s = CheckLength(where, absl::StrCat("centre[", i, "]"), l.centre[i]); !s.ok())
      return s;
    if (absl::Status s = CheckLength(where, absl::StrCat("size[", i, "]"), l.size[i]); !s.ok())
      return s;
  }
  if (absl::Status s = CheckLength(where, "height", l.height); !s.ok()) return s;
  if (j.contains("rotation_degrees")) {
    absl::StatusOr<double> r = Number(j["rotation_degrees"], where, "rotation_degrees");
    if (!r.ok()) return r.status();
    // 1e308° × π overflowed to inf and the light vanished; a million degrees
    // is thousands of turns, more than any animation needs.
    if (std::fabs(*r) > kMaxAreaLightDegrees)
      return Bad(where, "rotation_degrees", *r, " is beyond ±", kMaxAreaLightDegrees);
    l.rotation_degrees = *r;
  }
  if (j.contains("radiance")) {
    absl::StatusOr<std::array<double, 3>> c = Numbers<3>(j["radiance"], where, "radiance");
    if (!c.ok()) return c.status();
    if ((*c)[0] < 0 || (*c)[1] < 0 || (*c)[2] < 0) return Bad(where, "radiance", "must be ≥ 0");
    for (int i = 0; i < 3; ++i) {
      if ((*c)[i] > kMaxEnvRadiance)
        return Bad(where, absl::StrCat("radiance[", i, "]"), (*c)[i], " is above ", kMaxEnvRadiance,
                   " (the relighting's float sums would overflow)");
    }
    l.radiance = {float((*c)[0]), float((*c)[1]), float((*c)[2])};
  }
  if (j.contains("resolution")) {
    const json& r = j["resolution"];
    if (!r.is_number_integer()) return Bad(where, "resolution", "expected an integer");
    l.resolution = r.get<int>();
    if (l.resolution < 2 || l.resolution > 256 || (l.resolution & (l.resolution - 1)))
      return Bad(where, "resolution", l.resolution, " is not a power of two in 2..256");
  }
  if (j.contains("texture")) {
    if (!j["texture"].is_string()) return Bad(where, "texture", "expected a path string");
    std::filesystem::path path = j["texture"].get<std::string>();
    if (path.is_relative()) path = dir / path;
    absl::StatusOr<EnvMap> t = LoadTexture(path, where);
    if (!t.ok()) return t.status();
    l.texture = *std::move(t);
    l.texture_path = path.string();
  }
  if (absl::Status s = CheckEmitted(where, l); !s.ok()) return s;
  return l;
}

absl::StatusOr<std::vector<AreaLight>> LoadAreaLights(const std::filesystem::path& path) {
  absl::StatusOr<json> j = ReadJsonFile(path);
  if (!j.ok()) return j.status();
  const std::string where = absl::StrCat("area light '", path.string(), "'");
  const std::filesystem::path dir = path.parent_path();
  std::vector<AreaLight> lights;
  if (j->is_array()) {
    if (j->empty()) return Bad(where, "lights", "the array is empty");
    for (size_t i = 0; i < j->size(); ++i) {
      absl::StatusOr<AreaLight> l = ParseAreaLight((*j)[i], absl::StrCat(where, "[", i, "]"), dir);
      if (!l.ok()) return l.status();
      lights.push_back(*std::move(l));
    }
    return lights;
  }
  absl::StatusOr<AreaLight> l = ParseAreaLight(*j, where, dir);
  if (!l.ok()) return l.status();
  lights.push_back(*std::move(l));
  return lights;
}

double AreaLight::RotationRadians() const {
  return std::fmod(rotation_degrees, 360.0) * std::numbers::pi / 180;
}

AreaLight AreaLightSequence::Frame(int f) const {
  const double a = frames > 1 ? double(f) / (frames - 1) : 0;
  const auto mix = [a](double x, double y) { return x + a * (y - x); };
  AreaLight l = from;
  for (int i = 0; i < 2; ++i) {
    l.centre[i] = mix(from.centre[i], to.centre[i]);
    l.size[i] = mix(from.size[i], to.size[i]);
  }
  l.height = mix(from.height, to.height);
  l.rotation_degrees = mix(from.rotation_degrees, to.rotation_degrees);
  l.radiance = {float(mix(from.radiance.x, to.radiance.x)),
                float(mix(from.radiance.y, to.radiance.y)),
                float(mix(from.radiance.z, to.radiance.z))};
  return l;
}

absl::StatusOr<AreaLightSequence> LoadAreaLightSequence(const std::filesystem::path& path) {
  absl::StatusOr<json> j = ReadJsonFile(path);
  if (!j.ok()) return j.status();
  const std::string where = absl::StrCat("area light sequence '", path.string(), "'");
  if (!j->is_object()) return Bad(where, "sequence", "expected an object");
  for (const auto& [key, value] : j->items())
    if (key != "frames" && key != "from" && key != "to")
      return Bad(where, key, "unknown key (allowed: frames, from, to)");
  if (!j->contains("frames") || !(*j)["frames"].is_number_integer())
    return Bad(where, "frames", "missing or not an integer");
  AreaLightSequence seq;
  seq.frames = (*j)["frames"].get<int>();
  if (seq.frames < 1 || seq.frames > 100000) return Bad(where, "frames", "is not in 1..100000");
  if (!j->contains("from") || !j->contains("to")) return Bad(where, "from", "needs from and to");
  absl::StatusOr<AreaLight> from =
      ParseAreaLight((*j)["from"], where + ".from", path.parent_path());
  if (!from.ok()) return from.status();
  // "to" keeps whatever it does not give (texture and resolution always).
  json to = (*j)["from"];
  if (!(*j)["to"].is_object()) return Bad(where, "to", "expected an object");
  for (const auto& [key, value] : (*j)["to"].items()) {
    if (key == "texture" || key == "resolution")
      return Bad(where, absl::StrCat("to.", key), "comes from \"from\" (not interpolated)");
    to[key] = value;
  }
  to.erase("texture");
  absl::StatusOr<AreaLight> to_light = ParseAreaLight(to, where + ".to", path.parent_path());
  if (!to_light.ok()) return to_light.status();
  seq.from = *std::move(from);
  seq.to = *std::move(to_light);
  return seq;
}

}  // namespace wavebake
