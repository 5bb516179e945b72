#pragma once
// Reading a finished store (DESIGN.md §3). Shared by the runtime, `fetch`
// verification and tests.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "absl/status/statusor.h"
#include "core/bake/bake_params.h"
#include "core/columns/compressed_columns.h"
#include "core/layouts/samples.h"
#include "core/scene/scene.h"

namespace wavebake {

struct StoreInfo {
  nlohmann::json attrs;  // the root .zattrs as written by FINALIZE
  BakeParams params;     // parsed back from attrs["params"]
  // What LoadScene reads here: attrs["scene"] (builtin:NAME, or the scene
  // file's name) located on this machine (storage/store/store_scene.h).
  std::string scene_spec;
  std::string scene_hash;  // attrs["scene_hash"]
  int width = 0, height = 0, light_res = 0, columns = 0, bits = 0;
  // What FINALIZE recorded of its outputs (attrs "S" and stats.nnz); -1 when
  // the manifest does not say. The readers hold the arrays to them.
  int64_t samples = -1, nnz = -1;
};

// Errors: not a store, or attrs["format"] other than store::kFormat.
// Every reader below opens the arrays complete (ZarrArray::OpenComplete): a
// missing chunk, or an array whose length disagrees with the manifest, is
// DataLoss naming it.
absl::StatusOr<StoreInfo> ReadStoreInfo(const std::filesystem::path& store);
absl::StatusOr<SampleSet> ReadSamples(const std::filesystem::path& store);
// SceneHash of `scene` as the store's bake computed it (the uv layouts also
// hash their UV channel), to compare with info.scene_hash.
std::string StoreSceneHash(const StoreInfo& info, const Scene& scene);
// The whole matrix, dequantized and unscaled (core/columns/quantizer.h, DESIGN.md §1).
absl::StatusOr<CompressedColumns> ReadTransport(const std::filesystem::path& store);

// One decoded column: its depth and its kept coefficients (transform domain).
struct DecodedColumn {
  int depth = 0;
  std::vector<uint32_t> positions;
  std::vector<float> values;
};
absl::StatusOr<DecodedColumn> ReadColumn(const std::filesystem::path& store, int column);

}  // namespace wavebake
