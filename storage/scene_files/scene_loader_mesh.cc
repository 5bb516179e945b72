// Mesh files through assimp.
#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <fstream>
#include <optional>
#include <string>

#include "absl/strings/str_cat.h"
#include "storage/files/atomic_file.h"
#include "storage/scene_files/obj_rewrite.h"
#include "storage/scene_files/ply_rewrite.h"
#include "storage/scene_files/scene_loader_parts.h"

namespace wavebake {
namespace {

// assimp opens every file through this, the mesh file and those it names (an
// OBJ's mtllib, a glTF's buffers): a refused one is absent, read-only always.
// An OBJ's rewrite (storage/scene_files/obj_rewrite.h) stands in for the file under its
// own name, so that the material libraries it names resolve as before.
class ScopedIOSystem final : public Assimp::DefaultIOSystem {
 public:
  ScopedIOSystem(const SceneFiles& files, std::string name, std::string_view bytes)
      : files_(files), name_(std::move(name)), bytes_(bytes) {}
  bool Exists(const char* file) const override {
    if (Stands(file)) return true;
    const std::optional<std::filesystem::path> p = files_.Open(file);
    return p && DefaultIOSystem::Exists(p->c_str());
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string_view(mode).find_first_of("wa+") != std::string_view::npos) return nullptr;
    if (Stands(file))
      return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(bytes_.data()),
                                        bytes_.size());
    const std::optional<std::filesystem::path> p = files_.Open(file);
    if (!p) return nullptr;
    return DefaultIOSystem::Open(p->c_str(), mode);
  }

 private:
  bool Stands(const char* file) const { return !name_.empty() && name_ == file; }

  const SceneFiles& files_;
  const std::string name_;  // empty: none
  const std::string_view bytes_;
};

class FileErrors {
 public:
  FileErrors(const std::filesystem::path& path, const SceneFiles& files)
      : name_(files.Name(path)), files_(files) {}
  absl::Status operator()(const auto&... what) const {
    return absl::InvalidArgumentError(
        files_.Scrub(absl::StrCat("scene file '", name_, "': ", what...)));
  }

 private:
  std::string name_;
  const SceneFiles& files_;
};

// The material's diffuse colour, unless the file has no material and assimp
// made up its "DefaultMaterial" (whose colour is assimp's, not the author's).
Vec3 Albedo(const aiScene& scene, const aiMesh& mesh) {
  const Vec3 fallback = Mesh{}.albedo;
  if (mesh.mMaterialIndex >= scene.mNumMaterials) return fallback;
  const aiMaterial& mat = *scene.mMaterials[mesh.mMaterialIndex];
  aiString name;
  if (mat.Get(AI_MATKEY_NAME, name) == AI_SUCCESS &&
      std::string_view(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME)
    return fallback;
  aiColor3D c;
  if (mat.Get(AI_MATKEY_COLOR_DIFFUSE, c) != AI_SUCCESS) return fallback;
  // Clamped: files in the wild carry diffuse colours above 1, which are not
  // reflectances; CheckAndRepairScene would reject them.
  auto unit = [](float v) { return std::clamp(v, 0.0f, 1.0f); };
  return {unit(c.r), unit(c.g), unit(c.b)};
}

Mesh Convert(const aiScene& scene, const aiMesh& am, std::string name) {
  Mesh m;
  m.name = std::move(name);
  m.positions.reserve(am.mNumVertices);
  for (unsigned i = 0; i < am.mNumVertices; ++i)
    m.positions.push_back({am.mVertices[i].x, am.mVertices[i].y, am.mVertices[i].z});
  if (am.HasNormals()) {
    m.normals.reserve(am.mNumVertices);
    for (unsigned i = 0; i < am.mNumVertices; ++i)
      m.normals.push_back({am.mNormals[i].x, am.mNormals[i].y, am.mNormals[i].z});
  }
  // Channels in order, stopping at the first missing one (assimp keeps them
  // packed): a 3-component channel keeps its first two.
  for (unsigned c = 0; c < AI_MAX_NUMBER_OF_TEXTURECOORDS && am.HasTextureCoords(c); ++c) {
    std::vector<Vec2>& uv = m.uv_channels.emplace_back();
    uv.reserve(am.mNumVertices);
    for (unsigned i = 0; i < am.mNumVertices; ++i)
      uv.push_back({am.mTextureCoords[c][i].x, am.mTextureCoords[c][i].y});
  }
  // Points and lines survive aiProcess_Triangulate as 1- and 2-index faces;
  // they have no area to shade or occlude.
  for (unsigned f = 0; f < am.mNumFaces; ++f) {
    const aiFace& face = am.mFaces[f];
    if (face.mNumIndices == 3)
      m.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
  }
  m.albedo = Albedo(scene, am);
  return m;
}

std::string MeshName(const aiScene& scene, unsigned i, const std::filesystem::path& path) {
  const std::string stem = path.stem().string();
  if (scene.mNumMeshes == 1) return stem;
  return absl::StrCat(stem, "/", i, ":", scene.mMeshes[i]->mName.C_Str());
}

constexpr unsigned kMaxPolygon = 255;  // as PLY and OBJ are checked

// Before post-processing, which would merge NaN vertices away and fail with
// a puzzling message on a file without faces.
absl::Status CheckRaw(const aiScene& scene, const std::filesystem::path& path,
                      const FileErrors& error) {
  bool has_polygon = false;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i)
    for (unsigned f = 0; f < scene.mMeshes[i]->mNumFaces; ++f)
      has_polygon = has_polygon || scene.mMeshes[i]->mFaces[f].mNumIndices >= 3;
  if (!has_polygon) return error("has no triangles (an empty mesh)");
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    // assimp's post-processing trusts face indices: an out-of-range one in a
    // PLY crashed it (tests/fuzz/ply). Its readers do not all check them.
    // Triangulation trusts the mesh's primitive-type flags too: flags that
    // claim polygons no face has made Debian's assimp abort (tests/fuzz/ply).
    unsigned types = 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const unsigned n = m.mFaces[f].mNumIndices;
      if (n == 0) return error("mesh '", MeshName(scene, i, path), "': face ", f, " is empty");
      // Triangulation costs a polygon's corners squared (a face of 3 M
      // corners: days), whatever format it came in.
      if (n > kMaxPolygon)
        return error("mesh '", MeshName(scene, i, path), "': face ", f, " has ", n,
                     " corners (at most ", kMaxPolygon, " are read)");
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    if ((types & ~m.mPrimitiveTypes) != 0 ||
        ((m.mPrimitiveTypes & aiPrimitiveType_POLYGON) && !(types & aiPrimitiveType_POLYGON)))
      return error("mesh '", MeshName(scene, i, path),
                   "': its faces do not match its declared "
                   "primitive types (a malformed file)");
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices == nullptr || face.mIndices[k] >= m.mNumVertices)
          return error("mesh '", MeshName(scene, i, path), "': face ", f, " refers to vertex ",
                       face.mIndices ? face.mIndices[k] : 0, " of ", m.mNumVertices);
    }
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      const aiVector3D& p = m.mVertices[v];
      if (!IsFinite({p.x, p.y, p.z}))
        return error("mesh '", MeshName(scene, i, path), "': vertex ", v, " is not finite (", p.x,
                     ", ", p.y, ", ", p.z, ")");
    }
  }
  return absl::OkStatus();
}

// PLY by extension or by content, as assimp picks it by either (its content
// test takes "ply" followed by anything).
bool IsPly(const std::filesystem::path& path, std::string_view head) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".ply" || head.starts_with("ply");
}

bool IsObj(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".obj";
}

// An OBJ reaches assimp only as storage/scene_files/obj_rewrite.h writes it back.
absl::StatusOr<std::string> ReadObj(const std::filesystem::path& path, const FileErrors& error) {
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return error("cannot read: ", bytes.status().message());
  absl::StatusOr<std::string> text =
      RewriteObj(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
  if (!text.ok()) return error(text.status().message());
  return text;
}

// A PLY reaches assimp only as storage/scene_files/ply_rewrite.h writes it back.
absl::StatusOr<std::string> ReadPly(const std::filesystem::path& path, const FileErrors& error) {
  absl::StatusOr<std::vector<std::byte>> bytes = ReadFile(path);
  if (!bytes.ok()) return error("cannot read: ", bytes.status().message());
  absl::StatusOr<std::string> text =
      RewritePly(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
  if (!text.ok()) return error(text.status().message());
  return text;
}

}  // namespace

absl::StatusOr<std::vector<Mesh>> ReadMeshFile(const std::filesystem::path& path,
                                               const SceneFiles& files) {
  const FileErrors error(path, files);
  std::error_code ec;
  if (!files.Open(path) || !std::filesystem::is_regular_file(path, ec))
    return error("no such file");
  std::string head(3, '\0');
  std::ifstream(path, std::ios::binary).read(head.data(), 3);
  std::optional<std::string> ply;
  if (IsPly(path, head)) {
    absl::StatusOr<std::string> text = ReadPly(path, error);
    if (!text.ok()) return text.status();
    ply = std::move(*text);
  }
  std::string obj;
  if (!ply && IsObj(path)) {
    absl::StatusOr<std::string> text = ReadObj(path, error);
    if (!text.ok()) return text.status();
    obj = std::move(*text);
  }
  Assimp::Importer importer;
  // The importer owns the IO system.
  importer.SetIOHandler(
      std::make_unique<ScopedIOSystem>(files, IsObj(path) && !ply ? path.string() : "", obj)
          .release());
  // Read raw first: JoinIdenticalVertices silently merges a NaN vertex into
  // another one, so non-finite input must be caught before it runs.
  const aiScene* raw = ply ? importer.ReadFileFromMemory(ply->data(), ply->size(), 0, "ply")
                           : importer.ReadFile(path.string(), 0);
  if (raw == nullptr) return error("cannot read: ", importer.GetErrorString());
  if (absl::Status s = CheckRaw(*importer.GetScene(), path, error); !s.ok()) return s;
  // PreTransformVertices bakes the node hierarchy into world space, so a mesh
  // is a Mesh; JoinIdenticalVertices makes vertices (the hilbert layout's
  // samples) shared between faces again.
  const aiScene* ai = importer.ApplyPostProcessing(
      aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  if (ai == nullptr) return error("cannot process: ", importer.GetErrorString());
  std::vector<Mesh> meshes;
  for (unsigned i = 0; i < ai->mNumMeshes; ++i) {
    Mesh m = Convert(*ai, *ai->mMeshes[i], MeshName(*ai, i, path));
    if (!m.triangles.empty()) meshes.push_back(std::move(m));
  }
  if (meshes.empty()) return error("has no triangles (an empty mesh)");
  return meshes;
}

}  // namespace wavebake
