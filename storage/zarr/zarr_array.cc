#include "storage/zarr/zarr_array.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "storage/files/atomic_file.h"
#include "storage/files/json_file.h"
#include "storage/zarr/chunk_region.h"
#include "storage/zarr/delta_filter.h"
#include "storage/zarr/shuffle_filter.h"
#include "storage/zarr/zstd_codec.h"

namespace wavebake {
namespace {

constexpr char kZarray[] = ".zarray";

// Per-thread chunk buffers, reused chunk after chunk (storage/zarr/byte_buffer.h):
// a chunk's zstd frame, and its filtered bytes before compression.
enum ThreadBufferId { kFrame, kFiltered };
ByteBuffer& ThreadBuffer(ThreadBufferId id) {
  thread_local ByteBuffer buffers[2];
  return buffers[id];
}

}  // namespace

absl::StatusOr<ZarrArray> ZarrArray::Create(const std::filesystem::path& dir,
                                            const ArraySpec& spec) {
  if (absl::Status s = ValidateSpec(spec, (dir / kZarray).string()); !s.ok()) return s;
  absl::StatusOr<ZarrArray> existing = Open(dir);
  if (existing.ok()) {
    // The requested spec, which may carry what the .zarray does not (its zstd search).
    if (SameSpec(existing->spec(), spec)) return ZarrArray(dir, spec);
    return absl::AlreadyExistsError(absl::StrCat(
        (dir / kZarray).string(), ": an array with a different spec exists: ",
        ToZarray(existing->spec()).dump(), " (requested ", ToZarray(spec).dump(), ")"));
  }
  if (!absl::IsNotFound(existing.status())) return existing.status();
  if (absl::Status s = CreateDirectories(dir); !s.ok()) return s;
  if (absl::Status s = WriteJsonFile(dir / kZarray, ToZarray(spec)); !s.ok()) return s;
  return ZarrArray(dir, spec);
}

absl::StatusOr<ZarrArray> ZarrArray::Open(const std::filesystem::path& dir) {
  const std::filesystem::path path = dir / kZarray;
  absl::StatusOr<nlohmann::json> zarray = ReadJsonFile(path);
  if (absl::IsNotFound(zarray.status())) {
    return absl::NotFoundError(absl::StrCat(dir.string(), ": not a Zarr array (no .zarray)"));
  }
  if (!zarray.ok()) return zarray.status();
  absl::StatusOr<ArraySpec> spec = FromZarray(*zarray, path.string());
  if (!spec.ok()) return spec.status();
  return ZarrArray(dir, *std::move(spec));
}

absl::StatusOr<ZarrArray> ZarrArray::OpenComplete(const std::filesystem::path& dir) {
  absl::StatusOr<ZarrArray> a = Open(dir);
  if (a.ok()) a->complete_ = true;
  return a;
}

size_t ZarrArray::chunk_bytes() const {
  return static_cast<size_t>(ChunkElementCount(spec_)) * ItemSize(spec_.dtype);
}

std::filesystem::path ZarrArray::ChunkPath(std::span<const int64_t> chunk_index) const {
  return dir_ / ChunkKey(chunk_index);
}

absl::Status ZarrArray::CheckType(DType requested) const {
  if (requested == spec_.dtype) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat((dir_ / kZarray).string(), ": dtype is ",
                                                 ZarrName(spec_.dtype), ", not ",
                                                 ZarrName(requested)));
}

absl::Status ZarrArray::CheckChunkIndex(std::span<const int64_t> chunk_index) const {
  const std::vector<int64_t> grid = chunk_grid();
  bool ok = chunk_index.size() == grid.size();
  for (size_t d = 0; ok && d < grid.size(); ++d) {
    ok = chunk_index[d] >= 0 && chunk_index[d] < grid[d];
  }
  if (ok) return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrCat(dir_.string(), ": chunk index [", absl::StrJoin(chunk_index, ", "),
                   "] outside the chunk grid [", absl::StrJoin(grid, ", "), "]"));
}

absl::Status ZarrArray::WriteChunk(std::span<const int64_t> chunk_index,
                                   std::span<const std::byte> data) const {
  if (absl::Status s = CheckChunkIndex(chunk_index); !s.ok()) return s;
  if (data.size() != chunk_bytes()) {
    return absl::InvalidArgumentError(
        absl::StrCat(ChunkPath(chunk_index).string(), ": chunk data is ", data.size(),
                     " bytes, a full chunk is ", chunk_bytes(), " (edge chunks are padded)"));
  }
  ByteBuffer& frame = ThreadBuffer(kFrame);
  absl::Status compressed;
  if (spec_.delta_filter || spec_.shuffle_filter) {
    ByteBuffer& filtered = ThreadBuffer(kFiltered);
    filtered.assign(data.begin(), data.end());
    if (spec_.delta_filter) DeltaEncode(spec_.dtype, filtered);
    if (spec_.shuffle_filter) ShuffleEncode(ItemSize(spec_.dtype), filtered);
    compressed = ZstdCompressInto(filtered, spec_.zstd_level, frame, spec_.zstd_search);
  } else {
    compressed = ZstdCompressInto(data, spec_.zstd_level, frame, spec_.zstd_search);
  }
  if (!compressed.ok()) return compressed;
  return AtomicWriteFile(ChunkPath(chunk_index), frame);
}

absl::Status ZarrArray::ReadChunkInto(std::span<const int64_t> chunk_index,
                                      std::span<std::byte> out) const {
  if (absl::Status s = CheckChunkIndex(chunk_index); !s.ok()) return s;
  if (out.size() != chunk_bytes()) {
    return absl::InvalidArgumentError(absl::StrCat(dir_.string(), ": output buffer is ", out.size(),
                                                   " bytes, a chunk is ", chunk_bytes()));
  }
  const std::filesystem::path path = ChunkPath(chunk_index);
  ByteBuffer& frame = ThreadBuffer(kFrame);
  const absl::Status read = ReadFileInto(path, frame);
  if (absl::IsNotFound(read)) {
    if (complete_)
      return absl::DataLossError(absl::StrCat(path.string(), ": chunk [",
                                              absl::StrJoin(chunk_index, ", "),
                                              "] is missing (the array's shape needs it)"));
    FillElements(spec_.dtype, spec_.fill_value, out);
    return absl::OkStatus();
  }
  if (!read.ok()) return read;
  if (absl::Status s = ZstdDecompressInto(frame, out, path.string()); !s.ok()) return s;
  if (spec_.shuffle_filter) ShuffleDecode(ItemSize(spec_.dtype), out);
  if (spec_.delta_filter) DeltaDecode(spec_.dtype, out);
  return absl::OkStatus();
}

absl::Status ZarrArray::CopyChunkFrom(const ZarrArray& source,
                                      std::span<const int64_t> chunk_index) const {
  if (absl::Status s = CheckChunkIndex(chunk_index); !s.ok()) return s;
  if (!SameSpec(spec_, source.spec_))
    return absl::InvalidArgumentError(
        absl::StrCat(source.dir_.string(), " and ", dir_.string(), ": arrays of different specs"));
  ByteBuffer& frame = ThreadBuffer(kFrame);
  if (absl::Status s = ReadFileInto(source.ChunkPath(chunk_index), frame); !s.ok()) return s;
  return AtomicWriteFile(ChunkPath(chunk_index), frame);
}

absl::StatusOr<std::vector<std::byte>> ZarrArray::ReadChunk(
    std::span<const int64_t> chunk_index) const {
  std::vector<std::byte> out(chunk_bytes());
  if (absl::Status s = ReadChunkInto(chunk_index, out); !s.ok()) return s;
  return out;
}

}  // namespace wavebake
