#include "storage/store/store_verify.h"

#include <system_error>
#include <vector>

#include "absl/strings/str_cat.h"
#include "storage/store/store_check.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {

absl::StatusOr<int> VerifyStore(const std::filesystem::path& store) {
  // The final arrays whole and as the manifest says (a missing chunk would
  // otherwise pass: Zarr reads it as the fill value), then every array's chunks.
  if (absl::Status s = CheckStoreComplete(store); !s.ok()) return s;
  int arrays = 0;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(store, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->path().filename() != ".zarray") continue;
    absl::StatusOr<ZarrArray> array = ZarrArray::OpenComplete(it->path().parent_path());
    if (!array.ok()) return array.status();
    // Every chunk index, last axis fastest.
    const std::vector<int64_t> grid = array->chunk_grid();
    std::vector<int64_t> index(grid.size(), 0);
    bool empty = false;
    for (int64_t n : grid) empty = empty || n == 0;
    while (!empty) {
      if (absl::StatusOr<std::vector<std::byte>> c = array->ReadChunk(index); !c.ok())
        return c.status();
      size_t axis = index.size();
      while (axis > 0 && ++index[axis - 1] == grid[axis - 1]) index[--axis] = 0;
      if (axis == 0) break;
    }
    ++arrays;
  }
  if (ec) return absl::InternalError(absl::StrCat(store.string(), ": ", ec.message()));
  return arrays;
}

}  // namespace wavebake
