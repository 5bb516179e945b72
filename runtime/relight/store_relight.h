#pragma once
// Entry points of `wavebake relight` (DESIGN.md §5): a finished store opened
// for relighting, one relit image, and the whole command as one call.
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "core/layouts/samples.h"
#include "runtime/env/env_map.h"
#include "runtime/relight/relighter.h"
#include "storage/store_reader.h"

namespace wavebake {

struct OpenedStore {
  StoreInfo info;
  SampleSet samples;
  Relighter relighter;
};

// ReadStoreInfo + ReadSamples + ReadTransport (storage/store_reader.h) into a
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

// `wavebake relight STORE --env ENV --terms n --rotate DEG --out OUT`:
// ENV as LoadEnvMap reads it, rotated about +Y by rotate_degrees (Rotated);
// OUT by extension: .png (8-bit sRGB, × 2^exposure_stops, masked cells
// black) or .exr (linear float, masked NaN) of the W×H sample grid — the
// image itself for camera layouts; .ply (vertex colours on the scene
// reloaded from the store's scene spec) for the mesh layouts grid|hilbert;
// for uv layouts the lightmap (.png, .exr) or a glTF (.gltf, .glb), see
// WriteLightmapOutput.
// Errors name the bad argument (terms, rotate, out, env, store).
absl::Status RelightToFile(const std::filesystem::path& store, std::string_view env_spec, int terms,
                           double rotate_degrees, float exposure_stops,
                           const std::filesystem::path& out);

// One relit image [W*H*3] written by out's extension, as RelightToFile does.
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

}  // namespace wavebake
