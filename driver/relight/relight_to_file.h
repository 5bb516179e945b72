#pragma once
// `wavebake relight STORE --env ENV … --out OUT` as one call: the driver
// reads the environment (LoadEnvMap) and opens the store; runtime/ relights
// the opened store (runtime/relight/store_relight.h, Eq. 8; or
// runtime/glossy/glossy_store.h, the triple product) and writes the image.
#include <filesystem>
#include <string_view>

#include "absl/status/status.h"
#include "runtime/glossy/glossy_store.h"

namespace wavebake::driver {

// A diffuse store by Eq. 8: ENV as LoadEnvMap reads it, rotated about +Y by
// rotate_degrees (Rotated); OUT by extension: .png (8-bit sRGB, ×
// 2^exposure_stops, masked cells black) or .exr (linear float, masked NaN) of
// the W×H sample grid — the image itself for camera layouts; .ply (vertex
// colours on the scene reloaded from the store's scene spec) for the mesh
// layouts grid|hilbert; for uv layouts the lightmap (.png, .exr) or a glTF
// (.gltf, .glb), see WriteLightmapOutput. Errors name the bad argument
// (terms, rotate, out, env, store).
absl::Status RelightToFile(const std::filesystem::path& store, std::string_view env_spec, int terms,
                           double rotate_degrees, float exposure_stops,
                           const std::filesystem::path& out);

// A visibility store relit through the triple product with options.brdf, as
// RelightToFile writes it.
absl::Status RelightGlossyToFile(const std::filesystem::path& store, std::string_view env_spec,
                                 int terms, double rotate_degrees, float exposure_stops,
                                 const std::filesystem::path& out, const GlossyOptions& options);

// Any store: a visibility store by RelightGlossyToFile; a diffuse store by
// RelightToFile, which accepts lambert only and no eye (an error says why).
absl::Status RelightStoreToFile(const std::filesystem::path& store, std::string_view env_spec,
                                int terms, double rotate_degrees, float exposure_stops,
                                const std::filesystem::path& out, const GlossyOptions& options);

}  // namespace wavebake::driver
