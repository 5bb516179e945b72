#pragma once
// A finished store is whole (DESIGN.md §3): every final array FINALIZE writes
// is there, at the length its manifest (.zattrs "S", "M", stats.nnz) gives,
// with every chunk of its grid present, and its CSC matrix decodes. Zarr reads
// a missing chunk as the fill value, so a deleted chunk would otherwise read
// as zeros — a silently dark relighting. Used by fetch's verification.
#include <filesystem>
#include <optional>

#include "absl/status/status.h"

namespace wavebake {

// DataLoss naming the missing chunk or the array that disagrees with the
// manifest; the readers' errors (store_reader.h) otherwise.
absl::Status CheckStoreComplete(const std::filesystem::path& store);

// The first entry under `store` that no bake writes, if any: anything but a
// Zarr tree of group and array directories holding .zgroup, .zattrs,
// .zarray, chunk files ("0", "3.1") and atomic-write temporaries
// (storage/files/atomic_file.h). Replacing a store deletes it; a user's file there
// must not go with it.
std::optional<std::filesystem::path> ForeignStoreEntry(const std::filesystem::path& store);

}  // namespace wavebake
