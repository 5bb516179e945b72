#pragma once
// Helpers for the BAKE_TILE tests: a scratch store directory, a context, and
// reading the staging arrays back through the Zarr layer (an independent
// reader of what BakeTile wrote: chunk (g, t) as the layout of
// storage/store/store_layout.h and core/bake/job_plan.h defines it).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "tests/testing/scratch_dir.h"
#include "worker/tiles/bake_context.h"

namespace wavebake::staging_testing {

using test_support::ScratchDir;

inline std::unique_ptr<BakeContext> ContextOrDie(std::string_view spec, const BakeParams& p) {
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext(spec, p);
  EXPECT_TRUE(ctx.ok()) << ctx.status();
  return ctx.ok() ? *std::move(ctx) : nullptr;
}

// All chunks of one tile of staging/transport, read once; Row(cell) gathers
// the staged (row-transformed) row of T of one cell across the groups.
class StagedTile {
 public:
  StagedTile(const std::filesystem::path& store, const JobPlan& plan, int tile) : plan_(plan) {
    absl::StatusOr<ZarrArray> array = ZarrArray::Open(store::Path(store, store::kStagingTransport));
    EXPECT_TRUE(array.ok()) << array.status();
    if (!array.ok()) return;
    for (int g = 0; g < plan.groups; ++g) {
      const int64_t index[] = {g, tile};
      absl::StatusOr<std::vector<float>> chunk = array->ReadChunk<float>(index);
      EXPECT_TRUE(chunk.ok()) << chunk.status();
      if (chunk.ok()) chunks_.push_back(*std::move(chunk));
    }
  }
  bool ok() const { return static_cast<int>(chunks_.size()) == plan_.groups; }
  const std::vector<float>& chunk(int g) const { return chunks_[g]; }

  // cell: index inside the tile, row-major (cy * tile_w + cx).
  std::vector<float> Row(int cell) const {
    std::vector<float> row(plan_.columns);
    for (int m = 0; m < plan_.columns; ++m) {
      const int g = m / plan_.group_size, local = m % plan_.group_size;
      row[m] = chunks_[g][static_cast<size_t>(local) * plan_.tile_cells() + cell];
    }
    return row;
  }

 private:
  JobPlan plan_;
  std::vector<std::vector<float>> chunks_;
};

inline float StagedTileEnergy(const std::filesystem::path& store, int tile) {
  absl::StatusOr<ZarrArray> array = ZarrArray::Open(store::Path(store, store::kStagingTileEnergy));
  EXPECT_TRUE(array.ok()) << array.status();
  if (!array.ok()) return -1;
  const int64_t index[] = {tile};
  absl::StatusOr<std::vector<float>> chunk = array->ReadChunk<float>(index);
  EXPECT_TRUE(chunk.ok()) << chunk.status();
  return chunk.ok() ? (*chunk)[0] : -1;
}

// Every regular file under `dir` (relative path → bytes).
inline std::map<std::string, std::string> FileContents(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    files[std::filesystem::relative(e.path(), dir).string()] =
        std::string(std::istreambuf_iterator<char>(in), {});
  }
  return files;
}

}  // namespace wavebake::staging_testing
