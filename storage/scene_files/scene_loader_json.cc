// JSON scene files (DESIGN.md §5 SCENE):
//
//   {"meshes": [{"file": "bunny.obj",              // required; relative to this file
//                                                  // (uploaded: no absolute path, no "..")
//                "albedo": [0.8, 0.7, 0.6],        // optional, overrides the material
//                "transform": {"scale": 2 | [sx, sy, sz],   // optional, applied in
//                              "rotate_y_degrees": 30,      // this order: scale,
//                              "translate": [x, y, z]}}],   // rotate about +Y, translate
//    "camera": {"eye": [..], "target": [..],       // optional; eye and target required
//               "up": [0, 1, 0], "fov_y_degrees": 45}}
//
// Strict: an unknown key is an error (a typo must not silently mean a
// default), and so is a value of the wrong type; messages name the field.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <tuple>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "nlohmann/json.hpp"
#include "storage/scene_files/scene_loader.h"
#include "storage/scene_files/scene_loader_parts.h"

namespace wavebake {
namespace {

using nlohmann::json;

struct Transform {
  Vec3 scale{1, 1, 1};
  float rotate_y_degrees = 0;
  Vec3 translate{};
};

// Names the file in every error.
class Reader {
 public:
  Reader(std::filesystem::path path, const SceneFiles& files)
      : path_(std::move(path)), files_(files) {}
  const std::filesystem::path& path() const { return path_; }
  const SceneFiles& files() const { return files_; }

  absl::Status Error(const std::string& field, const auto&... what) const {
    return absl::InvalidArgumentError(absl::StrCat(Where(field), what...));
  }
  std::string Where(const std::string& field) const {
    return absl::StrCat("scene file '", files_.Name(path_), "': ", field,
                        field.empty() ? "" : ": ");
  }

  absl::Status CheckKeys(const json& obj, const std::string& field,
                         std::initializer_list<const char*> allowed) const {
    if (!obj.is_object()) return Error(field, "expected an object");
    for (const auto& item : obj.items()) {
      const std::string& key = item.key();
      if (std::find_if(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; }) ==
          allowed.end())
        return Error(field.empty() ? key : absl::StrCat(field, ".", key),
                     "unknown key (allowed: ", absl::StrJoin(allowed, ", "), ")");
    }
    return absl::OkStatus();
  }

  absl::StatusOr<float> Number(const json& v, const std::string& field) const {
    if (!v.is_number()) return Error(field, "expected a number, got ", v.dump());
    const double d = v.get<double>();
    if (!std::isfinite(d)) return Error(field, "is not finite");
    return static_cast<float>(d);
  }

  absl::StatusOr<Vec3> Vector(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != 3) return Error(field, "expected [x, y, z], got ", v.dump());
    float c[3];
    for (int i = 0; i < 3; ++i) {
      absl::StatusOr<float> x = Number(v[i], absl::StrCat(field, "[", i, "]"));
      if (!x.ok()) return x.status();
      c[i] = *x;
    }
    return Vec3{c[0], c[1], c[2]};
  }

 private:
  std::filesystem::path path_;
  const SceneFiles& files_;
};

absl::StatusOr<Transform> ReadTransform(const Reader& r, const json& j, const std::string& field) {
  if (absl::Status s = r.CheckKeys(j, field, {"translate", "scale", "rotate_y_degrees"}); !s.ok())
    return s;
  Transform t;
  if (auto it = j.find("translate"); it != j.end()) {
    absl::StatusOr<Vec3> v = r.Vector(*it, field + ".translate");
    if (!v.ok()) return v.status();
    t.translate = *v;
  }
  if (auto it = j.find("scale"); it != j.end()) {
    absl::StatusOr<Vec3> v;
    if (it->is_number()) {
      absl::StatusOr<float> s = r.Number(*it, field + ".scale");
      if (!s.ok()) return s.status();
      v = Vec3{*s, *s, *s};  // uniform
    } else {
      v = r.Vector(*it, field + ".scale");
      if (!v.ok()) return r.Error(field + ".scale", "expected a number or [x, y, z]");
    }
    if (v->x == 0 || v->y == 0 || v->z == 0) return r.Error(field + ".scale", "must not be zero");
    t.scale = *v;
  }
  if (auto it = j.find("rotate_y_degrees"); it != j.end()) {
    absl::StatusOr<float> a = r.Number(*it, field + ".rotate_y_degrees");
    if (!a.ok()) return a.status();
    t.rotate_y_degrees = *a;
  }
  return t;
}

void Apply(const Transform& t, Mesh& m) {
  const float a = t.rotate_y_degrees * std::numbers::pi_v<float> / 180;
  const float c = std::cos(a), s = std::sin(a);
  auto rotate = [&](Vec3 v) { return Vec3{c * v.x + s * v.z, v.y, -s * v.x + c * v.z}; };
  auto mul = [](Vec3 u, Vec3 v) { return Vec3{u.x * v.x, u.y * v.y, u.z * v.z}; };
  const Vec3 inverse_scale{1 / t.scale.x, 1 / t.scale.y, 1 / t.scale.z};
  for (Vec3& p : m.positions) p = rotate(mul(p, t.scale)) + t.translate;
  // Normals transform by the inverse transpose: R · S⁻¹ (renormalized later).
  for (Vec3& n : m.normals) n = rotate(mul(n, inverse_scale));
  // A mirror turns the surface inside out; swapping two indices turns it back.
  if (t.scale.x * t.scale.y * t.scale.z < 0)
    for (auto& tri : m.triangles) std::swap(tri[1], tri[2]);
}

absl::Status ReadMeshEntry(const Reader& r, const json& j, int index, Scene& scene,
                           std::vector<std::string>& warnings) {
  const std::string field = absl::StrCat("meshes[", index, "]");
  if (absl::Status s = r.CheckKeys(j, field, {"file", "albedo", "transform"}); !s.ok()) return s;
  const auto file = j.find("file");
  if (file == j.end() || !file->is_string())
    return r.Error(field + ".file", "expected a path string");
  const std::string reference = file->get<std::string>();
  std::string warning;
  absl::StatusOr<std::filesystem::path> mesh_path =
      r.files().Resolve(r.path(), reference, &warning);
  if (!mesh_path.ok()) return r.Error(field + ".file", mesh_path.status().message());
  if (!warning.empty()) warnings.push_back(r.Where(field + ".file") + warning);
  if (mesh_path->extension() == ".json")
    return r.Error(field + ".file", "scene files do not nest: '", reference, "'");
  Transform transform;
  if (auto it = j.find("transform"); it != j.end()) {
    absl::StatusOr<Transform> t = ReadTransform(r, *it, field + ".transform");
    if (!t.ok()) return t.status();
    transform = *t;
  }
  std::optional<Vec3> albedo;
  if (auto it = j.find("albedo"); it != j.end()) {
    absl::StatusOr<Vec3> a = r.Vector(*it, field + ".albedo");
    if (!a.ok()) return a.status();
    if (Min(*a, {0, 0, 0}) != Vec3{0, 0, 0} || Max(*a, {1, 1, 1}) != Vec3{1, 1, 1})
      return r.Error(field + ".albedo", "components must be in [0, 1]");
    albedo = *a;
  }
  absl::StatusOr<std::vector<Mesh>> meshes = ReadMeshFile(*mesh_path, r.files());
  if (!meshes.ok()) return r.Error(field + ".file", meshes.status().message());
  for (Mesh& m : *meshes) {
    Apply(transform, m);
    if (albedo) m.albedo = *albedo;
    scene.meshes.push_back(std::move(m));
  }
  return absl::OkStatus();
}

absl::StatusOr<Camera> ReadCamera(const Reader& r, const json& j) {
  if (absl::Status s = r.CheckKeys(j, "camera", {"eye", "target", "up", "fov_y_degrees"}); !s.ok())
    return s;
  Camera c;
  for (auto [key, dst, required] :
       {std::tuple{"eye", &c.eye, true}, std::tuple{"target", &c.target, true},
        std::tuple{"up", &c.up, false}}) {
    const auto it = j.find(key);
    if (it == j.end()) {
      if (required) return r.Error(absl::StrCat("camera.", key), "missing");
      continue;
    }
    absl::StatusOr<Vec3> v = r.Vector(*it, absl::StrCat("camera.", key));
    if (!v.ok()) return v.status();
    *dst = *v;
  }
  if (auto it = j.find("fov_y_degrees"); it != j.end()) {
    absl::StatusOr<float> f = r.Number(*it, "camera.fov_y_degrees");
    if (!f.ok()) return f.status();
    c.fov_y_degrees = *f;
  }
  return c;
}

// The file's top level, with its keys and its meshes array checked.
absl::StatusOr<json> ParseSceneFile(const Reader& r) {
  if (!r.files().Open(r.path())) return r.Error("", "is outside the scene's files");
  std::ifstream in(r.path());
  if (!in) return r.Error("", "cannot open (missing or unreadable)");
  std::stringstream text;
  text << in.rdbuf();
  json j;
  try {
    j = json::parse(text.str());
  } catch (const json::parse_error& e) {  // the library's only way to say where
    return r.Error("", "is not valid JSON: ", e.what());
  } catch (const json::exception& e) {  // e.g. a number too large for any type (tests/fuzz/json)
    return r.Error("", "is not usable JSON: ", e.what());
  }
  if (absl::Status s = r.CheckKeys(j, "", {"meshes", "camera"}); !s.ok()) return s;
  const auto meshes = j.find("meshes");
  if (meshes == j.end() || !meshes->is_array() || meshes->empty())
    return r.Error("meshes", "expected a non-empty array of meshes");
  return j;
}

}  // namespace

absl::StatusOr<std::vector<std::string>> JsonSceneMeshFiles(const std::filesystem::path& path,
                                                            const SceneFiles* files) {
  const std::unique_ptr<SceneFiles> local = files ? nullptr : LocalSceneFiles();
  const Reader r(path, files ? *files : *local);
  absl::StatusOr<json> j = ParseSceneFile(r);
  if (!j.ok()) return j.status();
  std::vector<std::string> references;
  for (size_t i = 0; i < (*j)["meshes"].size(); ++i) {
    const json& m = (*j)["meshes"][i];
    const std::string field = absl::StrCat("meshes[", i, "].file");
    if (!m.is_object() || !m.contains("file") || !m["file"].is_string())
      return r.Error(field, "expected a path string");
    references.push_back(m["file"].get<std::string>());
  }
  return references;
}

absl::StatusOr<Scene> ReadJsonScene(const std::filesystem::path& path, const SceneFiles& files,
                                    std::vector<std::string>& warnings) {
  const Reader r(path, files);
  absl::StatusOr<json> parsed = ParseSceneFile(r);
  if (!parsed.ok()) return parsed.status();
  const json& j = *parsed;
  const auto meshes = j.find("meshes");
  Scene scene;
  scene.name = path.stem().string();
  for (size_t i = 0; i < meshes->size(); ++i)
    if (absl::Status s = ReadMeshEntry(r, (*meshes)[i], static_cast<int>(i), scene, warnings);
        !s.ok())
      return s;
  if (auto it = j.find("camera"); it != j.end()) {
    absl::StatusOr<Camera> c = ReadCamera(r, *it);
    if (!c.ok()) return c.status();
    scene.camera = *c;
  }
  return scene;
}

}  // namespace wavebake
