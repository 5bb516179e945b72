#pragma once
// The scene harnesses (obj, ply, json): the input is an uploaded scene file,
// loaded as the coordinator loads one (confined to its upload directory,
// storage/scene_files/scene_files.h). Beside that directory lie a mesh and a material
// library with values found nowhere else: a scene that loads either broke
// out of its upload. A loaded scene must be what CheckAndRepairScene promises.
#include <cmath>

#include "core/scene/scene.h"
#include "storage/scene_files/scene_files.h"
#include "storage/scene_files/scene_loader.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {

inline constexpr float kOutsideX = 4242.5f;
inline const Vec3 kOutsideAlbedo{0.125f, 0.375f, 0.625f};

inline const std::filesystem::path& UploadDir() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path root = ScratchDir() / "upload";
    std::filesystem::create_directories(root);
    WriteBytes(ScratchDir() / "outside.obj",
               "mtllib outside.mtl\nv 4242.5 0 0\nv 4243 0 0\nv 4242.5 1 0\nusemtl x\nf 1 2 3\n");
    WriteBytes(ScratchDir() / "outside.mtl", "newmtl x\nKd 0.125 0.375 0.625\n");
    WriteBytes(root / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    return root;
  }();
  return dir;
}

inline void CheckScene(const Scene& scene) {
  Require(!scene.meshes.empty(), "a scene has meshes");
  for (const Mesh& m : scene.meshes) {
    Require(!m.triangles.empty() && m.normals.size() == m.positions.size(), "repaired mesh");
    Require(m.albedo != kOutsideAlbedo, "read a material library outside the upload");
    for (const auto& t : m.triangles)
      for (uint32_t v : t) Require(v < m.positions.size(), "vertex index in range");
    for (size_t i = 0; i < m.positions.size(); ++i) {
      Require(IsFinite(m.positions[i]), "finite vertex");
      Require(m.positions[i].x != kOutsideX, "read a mesh outside the upload");
      Require(std::fabs(Length(m.normals[i]) - 1) < 1e-3f, "unit normal");
    }
  }
}

// Writes the input as UploadDir()/name and loads it confined to UploadDir().
inline int FuzzSceneFile(const uint8_t* data, size_t size, const char* name) {
  const std::filesystem::path path = UploadDir() / name;
  WriteBytes(path, std::string_view(reinterpret_cast<const char*>(data), size));
  static const std::unique_ptr<SceneFiles> files = ConfinedSceneFiles(UploadDir());
  absl::StatusOr<Scene> scene = LoadScene(path.string(), nullptr, files.get());
  if (scene.ok()) {
    CheckScene(*scene);
  } else {
    Require(scene.status().code() == absl::StatusCode::kInvalidArgument, "errors are bad input");
    // Quoting the client's own text is no leak: only a path it did not write.
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    if (input.find(ScratchDir().string()) == std::string_view::npos)
      Require(scene.status().message().find(ScratchDir().string()) == std::string_view::npos,
              "an error names a server path");
  }
  return 0;
}

}  // namespace wavebake::fuzz
