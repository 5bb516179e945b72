#pragma once
// The root .zattrs of a finished store (DESIGN.md §3): format, scene, job
// params, grid and cubemap sizes, filters, bits, the dither formula and the
// stats — everything a reader needs besides the arrays, and enough to tell
// how a store was made.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "worker/tiles/bake_context.h"

namespace wavebake {

struct ManifestBits {
  int bits = 0;             // max-normalized rules: b of every column; uniform auto: the widest
  int bits_needed = 0;      // what --bits auto asks (worker/columns/finalize.cc AutoBits)
  int max_column_bits = 0;  // the largest single column's need
};

nlohmann::json StoreManifest(const BakeContext& ctx, ManifestBits bits, nlohmann::json stats);

// On-disk bytes of every file under `dir` (an array: its chunks and .zarray),
// without AtomicWriteFile's temp files (storage/files/atomic_file.h).
uint64_t DirectoryBytes(const std::filesystem::path& dir);

// "bytes" of the stats: each final array's size on disk, the transport total,
// the raw float32 size S·M·4 of T and their ratio.
nlohmann::json StoreBytes(const BakeContext& ctx, const std::filesystem::path& store);

}  // namespace wavebake
