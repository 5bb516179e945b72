#pragma once
// Relighting a finished store (DESIGN.md §5 relight): the store opened for
// relighting, one relit image, and its output file (the command that ties
// them together: driver/relight/relight_to_file.h).
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/relighter.h"
#include "storage/store/store_reader.h"

namespace wavebake {

struct OpenedStore {
  StoreInfo info;
  SampleSet samples;
  Relighter relighter;
};

// ReadStoreInfo + ReadSamples + ReadTransport (storage/store/store_reader.h) into a
// Relighter. Errors: not a store, another format version, inconsistent arrays
// (named by the reader or Relighter::Create).
absl::StatusOr<OpenedStore> OpenStore(const std::filesystem::path& store);

// Environment lighting needs the six cube faces: a store baked over one plane
// face (--light-domain plane:S) is relit by area lights (runtime/near_field/near_field.h).
// FailedPrecondition naming the store's light domain otherwise.
absl::Status RequireCubeDomain(const StoreInfo& info);

// The store relit by `terms` area-weighted wavelet lights of env (lat-long):
// [W*H*3] linear RGB × albedo, NaN in masked cells. Error: terms ≤ 0.
absl::StatusOr<std::vector<float>> RelightImage(OpenedStore& store, const EnvMap& env, int terms);

// One relit image [W*H*3] written by out's extension (driver/relight/relight_to_file.h
// RelightToFile says which).
absl::Status WriteRelit(const OpenedStore& store, std::span<const float> rgb, float exposure_stops,
                        const std::filesystem::path& out);
absl::Status WriteRelit(const StoreInfo& info, const SampleSet& samples, std::span<const float> rgb,
                        float exposure_stops, const std::filesystem::path& out);
// Error unless out ends in .png, .exr, .ply, .gltf or .glb (checked before
// any work; WriteRelit says which of them the store's layout can write).
absl::Status CheckRelitPath(const std::filesystem::path& out);

// WriteRelit of a uv store (runtime/io/lightmap.h): .png (tone-mapped like any
// PNG) and .exr (linear; 0 beyond the gutters, where engines would choke on
// NaN) lightmaps with gutters of kLightmapGutter texels; .gltf/.glb, the
// scene reloaded from the store's scene spec (its hash checked) with the
// gutter-dilated PNG lightmap as its texture. Error: .ply or another extension.
absl::Status WriteLightmapOutput(const StoreInfo& info, const SampleSet& samples,
                                 std::span<const float> rgb, float exposure_stops,
                                 const std::filesystem::path& out);

// A uv store's meshes as one triangle list for a viewer (the GPU view's 3D
// mode): positions, every vertex's lightmap position in texel units of the
// W×H grid (x right, y down from row 0, the grid's own convention; through
// LightmapUvs of runtime/io/lightmap.h), and the triangles. The scene is
// reloaded from the store's spec and checked against its hash. Errors: not
// a uv layout (named), the scene (as for glTF output).
struct LightmapMesh {
  std::vector<float> positions;   // 3 a vertex
  std::vector<float> texels;      // 2 a vertex
  std::vector<uint32_t> indices;  // 3 a triangle
};
absl::StatusOr<LightmapMesh> LightmapMeshOf(const StoreInfo& info, const SampleSet& samples);

}  // namespace wavebake
