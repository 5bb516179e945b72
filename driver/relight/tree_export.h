#pragma once
// `wavebake export STORE --format wavelet-tree --out DIR` (and the viewer's
// in-memory copy): a finished diffuse store's rows as Boulton's wavelet-tree
// textures (runtime/gpu/wavelet_tree.h), written as DIR/header.json plus the raw
// little-endian arrays it names.
#include <filesystem>

#include "absl/status/statusor.h"
#include "core/columns/compressed_columns.h"
#include "core/layouts/samples.h"
#include "nlohmann/json.hpp"
#include "runtime/gpu/wavelet_tree.h"

namespace wavebake::driver {

// A store opened for both GPU modes: its samples and decoded columns.
struct TreeSource {
  SampleSet samples;
  CompressedColumns columns;
};
// Errors: not a store; a store the trees cannot hold — visibility rows, a
// plane light domain, Daubechies-4 rows — named by field.
absl::StatusOr<TreeSource> OpenTreeSource(const std::filesystem::path& store);
// The trees of an opened store (the columns are decoded, not consumed).
absl::StatusOr<WaveletTreeTextures> WaveletTreesOf(const TreeSource& source,
                                                   const WaveletTreeOptions& options);

// The store's trees. Errors: not a store; a store the trees cannot hold —
// visibility rows, a plane light domain, Daubechies-4 rows — named by field.
absl::StatusOr<WaveletTreeTextures> StoreWaveletTrees(const std::filesystem::path& store,
                                                      const WaveletTreeOptions& options);

// StoreWaveletTrees written to `out` (created; each file written atomically);
// returns the header written.
absl::StatusOr<nlohmann::json> ExportWaveletTrees(const std::filesystem::path& store,
                                                  const std::filesystem::path& out,
                                                  const WaveletTreeOptions& options);

}  // namespace wavebake::driver
