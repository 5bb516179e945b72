#pragma once
// A Zarr v2 array on disk (DESIGN.md §3): .zarray metadata plus one file per
// chunk ("i.j"), each a single zstd frame with content size and checksum.
//
// Thread- and process-safety: a ZarrArray is immutable after Create/Open, so
// one object may be shared by threads. Distinct chunks may be written
// concurrently from any number of threads or processes; rewriting the same
// chunk (a retried task, DESIGN.md §4) is safe because every file is replaced
// atomically, and readers see the old or the new chunk, never a mix.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "storage/zarr/array_spec.h"
#include "storage/zarr/zarr_group.h"  // arrays live in groups; one include serves both

namespace wavebake {

class ZarrArray {
 public:
  // Creates `dir` (and parents) and writes .zarray atomically. Idempotent for
  // retried tasks: if `dir` already holds an array with the same spec it is
  // opened as is (chunks kept); a different spec is AlreadyExists.
  static absl::StatusOr<ZarrArray> Create(const std::filesystem::path& dir, const ArraySpec& spec);
  // NotFound if `dir` has no .zarray; InvalidArgument naming the file and
  // field if the metadata is not an array this layer can read.
  static absl::StatusOr<ZarrArray> Open(const std::filesystem::path& dir);
  // Open, for an array that must hold every chunk of its grid (a finished
  // store's arrays, DESIGN.md §3): reading a missing chunk is DataLoss naming
  // it, not the fill value (a deleted chunk must not read as zeros).
  static absl::StatusOr<ZarrArray> OpenComplete(const std::filesystem::path& dir);

  const std::filesystem::path& dir() const { return dir_; }
  const ArraySpec& spec() const { return spec_; }
  std::vector<int64_t> chunk_grid() const { return ChunkGrid(spec_); }
  // Bytes of one full chunk (edge chunks too: they are padded).
  size_t chunk_bytes() const;
  std::filesystem::path ChunkPath(std::span<const int64_t> chunk_index) const;

  // `data` is the full chunk in C order; for an edge chunk the part beyond the
  // array's end is padding (readers ignore it; use the fill value to keep
  // stores deterministic).
  absl::Status WriteChunk(std::span<const int64_t> chunk_index,
                          std::span<const std::byte> data) const;
  // A chunk that was never written reads as the fill value (OpenComplete:
  // DataLoss). Corruption is DataLoss.
  absl::StatusOr<std::vector<std::byte>> ReadChunk(std::span<const int64_t> chunk_index) const;
  absl::Status ReadChunkInto(std::span<const int64_t> chunk_index, std::span<std::byte> out) const;
  // Chunk `chunk_index` of `source`, an array of the same spec, written here
  // as it is encoded, without decoding it: a chunk known to hold the same
  // values costs a file copy instead of a decode and an encode. Corruption
  // travels with it and is found where the chunk is read. InvalidArgument if
  // the specs differ, NotFound if the source never wrote the chunk.
  absl::Status CopyChunkFrom(const ZarrArray& source, std::span<const int64_t> chunk_index) const;

  // Typed chunk I/O: T must be the array's element type (InvalidArgument otherwise).
  template <class T>
  absl::Status WriteChunk(std::span<const int64_t> chunk_index, std::span<const T> data) const;
  template <class T>
  absl::StatusOr<std::vector<T>> ReadChunk(std::span<const int64_t> chunk_index) const;

  // The whole array in C order (ElementCount(spec()) values), chunked
  // automatically; for 1-D and other arrays that fit in memory.
  template <class T>
  absl::Status WriteAll(std::span<const T> values) const;
  template <class T>
  absl::StatusOr<std::vector<T>> ReadAll() const;

 private:
  ZarrArray(std::filesystem::path dir, ArraySpec spec)
      : dir_(std::move(dir)), spec_(std::move(spec)) {}
  absl::Status CheckType(DType requested) const;
  absl::Status CheckChunkIndex(std::span<const int64_t> chunk_index) const;
  absl::Status WriteAllBytes(std::span<const std::byte> values) const;
  absl::Status ReadAllBytes(std::span<std::byte> out) const;

  std::filesystem::path dir_;
  ArraySpec spec_;
  bool complete_ = false;  // OpenComplete
};

// ---- template definitions ----

template <class T>
absl::Status ZarrArray::WriteChunk(std::span<const int64_t> chunk_index,
                                   std::span<const T> data) const {
  if (absl::Status s = CheckType(DTypeOf<T>()); !s.ok()) return s;
  return WriteChunk(chunk_index, std::as_bytes(data));
}

template <class T>
absl::StatusOr<std::vector<T>> ZarrArray::ReadChunk(std::span<const int64_t> chunk_index) const {
  if (absl::Status s = CheckType(DTypeOf<T>()); !s.ok()) return s;
  std::vector<T> out(static_cast<size_t>(ChunkElementCount(spec_)));
  if (absl::Status s = ReadChunkInto(chunk_index, std::as_writable_bytes(std::span(out)));
      !s.ok()) {
    return s;
  }
  return out;
}

template <class T>
absl::Status ZarrArray::WriteAll(std::span<const T> values) const {
  if (absl::Status s = CheckType(DTypeOf<T>()); !s.ok()) return s;
  return WriteAllBytes(std::as_bytes(values));
}

template <class T>
absl::StatusOr<std::vector<T>> ZarrArray::ReadAll() const {
  if (absl::Status s = CheckType(DTypeOf<T>()); !s.ok()) return s;
  std::vector<T> out(static_cast<size_t>(ElementCount(spec_)));
  if (absl::Status s = ReadAllBytes(std::as_writable_bytes(std::span(out))); !s.ok()) return s;
  return out;
}

}  // namespace wavebake
