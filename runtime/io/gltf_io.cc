// glTF half of lightmap.h: the baked meshes and their lightmap through
// assimp's glTF 2.0 exporter.
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Exporter.hpp>
#include <cctype>
#include <cstring>
#include <memory>
#include <string>

#include "absl/strings/str_cat.h"
#include "runtime/io/lightmap.h"
#include "storage/files/scoped_dir.h"

namespace wavebake {
namespace {

// aiScene owns everything it points to and frees it with delete / delete[]
// (assimp's ownership model), so these allocations are handed straight to it.
aiMesh* ToAiMesh(const Mesh& m, const std::vector<Vec2>& uv) {
  auto out = std::make_unique<aiMesh>();
  out->mName = aiString(m.name);
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mMaterialIndex = 0;
  out->mNumVertices = static_cast<unsigned>(m.positions.size());
  out->mVertices = new aiVector3D[out->mNumVertices];
  out->mNormals = new aiVector3D[out->mNumVertices];
  out->mTextureCoords[0] = new aiVector3D[out->mNumVertices];
  out->mNumUVComponents[0] = 2;
  for (unsigned i = 0; i < out->mNumVertices; ++i) {
    out->mVertices[i] = {m.positions[i].x, m.positions[i].y, m.positions[i].z};
    out->mNormals[i] = {m.normals[i].x, m.normals[i].y, m.normals[i].z};
    out->mTextureCoords[0][i] = {uv[i].u, uv[i].v, 0};
  }
  out->mNumFaces = static_cast<unsigned>(m.triangles.size());
  out->mFaces = new aiFace[out->mNumFaces];
  for (unsigned f = 0; f < out->mNumFaces; ++f) {
    out->mFaces[f].mNumIndices = 3;
    out->mFaces[f].mIndices = new unsigned[3];
    std::copy(m.triangles[f].begin(), m.triangles[f].end(), out->mFaces[f].mIndices);
  }
  return out.release();
}

// The lightmap holds outgoing radiance, so the material emits it: black
// base colour and the lightmap as emissive texture (emissive factor 1) show
// exactly the baked result in any glTF viewer, whatever lights the viewer
// adds (assimp 5.2's exporter writes no KHR_materials_unlit).
aiMaterial* LightmapMaterial() {
  auto mat = std::make_unique<aiMaterial>();
  const aiString name("wavebake lightmap");
  mat->AddProperty(&name, AI_MATKEY_NAME);
  const aiString texture("*0");  // the scene's embedded texture 0
  mat->AddProperty(&texture, AI_MATKEY_TEXTURE_EMISSIVE(0));
  const aiColor4D black(0, 0, 0, 1);
  mat->AddProperty(&black, 1, AI_MATKEY_BASE_COLOR);
  mat->AddProperty(&black, 1, AI_MATKEY_COLOR_DIFFUSE);
  const aiColor3D white(1, 1, 1);
  mat->AddProperty(&white, 1, AI_MATKEY_COLOR_EMISSIVE);
  const int clamp = aiTextureMapMode_Clamp;
  mat->AddProperty(&clamp, 1, AI_MATKEY_MAPPINGMODE_U_EMISSIVE(0));
  mat->AddProperty(&clamp, 1, AI_MATKEY_MAPPINGMODE_V_EMISSIVE(0));
  const float metallic = 0, roughness = 1;
  mat->AddProperty(&metallic, 1, AI_MATKEY_METALLIC_FACTOR);
  mat->AddProperty(&roughness, 1, AI_MATKEY_ROUGHNESS_FACTOR);
  return mat.release();
}

aiTexture* EmbeddedPng(std::span<const std::byte> png) {
  auto tex = std::make_unique<aiTexture>();
  tex->mWidth = static_cast<unsigned>(png.size());  // compressed: mWidth bytes, mHeight 0
  tex->mHeight = 0;
  std::strncpy(tex->achFormatHint, "png", sizeof(tex->achFormatHint) - 1);
  tex->mFilename = aiString("lightmap.png");
  tex->pcData = new aiTexel[(png.size() + sizeof(aiTexel) - 1) / sizeof(aiTexel)];
  std::memcpy(tex->pcData, png.data(), png.size());
  return tex.release();
}

std::unique_ptr<aiScene> BuildScene(const Scene& scene, const std::vector<std::vector<Vec2>>& uvs,
                                    std::span<const std::byte> png) {
  auto ai = std::make_unique<aiScene>();
  const unsigned n = static_cast<unsigned>(scene.meshes.size());
  ai->mNumMeshes = n;
  ai->mMeshes = new aiMesh*[n];
  for (unsigned i = 0; i < n; ++i) ai->mMeshes[i] = ToAiMesh(scene.meshes[i], uvs[i]);
  ai->mNumMaterials = 1;
  ai->mMaterials = new aiMaterial* [1] { LightmapMaterial() };
  ai->mNumTextures = 1;
  ai->mTextures = new aiTexture* [1] { EmbeddedPng(png) };
  // One child node per mesh: the exporter would merge a node's meshes into
  // one glTF mesh and lose their names.
  ai->mRootNode = new aiNode(scene.name.empty() ? "wavebake" : scene.name);
  ai->mRootNode->mNumChildren = n;
  ai->mRootNode->mChildren = new aiNode*[n];
  for (unsigned i = 0; i < n; ++i) {
    aiNode* child = new aiNode(scene.meshes[i].name);
    child->mParent = ai->mRootNode;
    child->mNumMeshes = 1;
    child->mMeshes = new unsigned[1]{i};
    ai->mRootNode->mChildren[i] = child;
  }
  return ai;
}

}  // namespace

absl::Status WriteLightmapGltf(const std::filesystem::path& out, const Scene& scene,
                               const std::vector<std::vector<Vec2>>& lightmap_uvs,
                               std::span<const std::byte> png) {
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".gltf" && ext != ".glb")
    return absl::InvalidArgumentError(absl::StrCat("out: ", out.string(), ": not .gltf or .glb"));
  if (lightmap_uvs.size() != scene.meshes.size())
    return absl::InvalidArgumentError("lightmap UVs: one list per mesh expected");
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    if (lightmap_uvs[i].size() != scene.meshes[i].positions.size() ||
        scene.meshes[i].normals.size() != scene.meshes[i].positions.size())
      return absl::InvalidArgumentError(
          absl::StrCat("mesh '", scene.meshes[i].name, "': UVs or normals do not match vertices"));
  }
  const std::unique_ptr<aiScene> ai = BuildScene(scene, lightmap_uvs, png);
  // Exported into a private directory beside `out` under the final names
  // (the .gltf names its .bin), then moved into place, .gltf last.
  absl::StatusOr<ScopedDir> work = ScopedDir::CreateBeside(out, "gltf");
  if (!work.ok()) return work.status();
  const std::filesystem::path staged = work->path() / out.filename();
  Assimp::Exporter exporter;
  if (exporter.Export(ai.get(), ext == ".glb" ? "glb2" : "gltf2", staged.string()) != AI_SUCCESS)
    return absl::InternalError(
        absl::StrCat("out: ", out.string(), ": glTF export failed: ", exporter.GetErrorString()));
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(work->path(), ec)) {
    if (entry.path().filename() == out.filename()) continue;
    std::filesystem::rename(entry.path(), out.parent_path() / entry.path().filename(), ec);
    if (ec) break;
  }
  if (!ec) std::filesystem::rename(staged, out, ec);
  if (ec) return absl::InternalError(absl::StrCat("out: ", out.string(), ": ", ec.message()));
  return absl::OkStatus();
}

}  // namespace wavebake
