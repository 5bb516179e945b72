#pragma once
// Whole-file I/O for the store. Writes are atomic (DESIGN.md §3): readers and
// concurrent or retried writers of the same file see either the old or the new
// contents, never a partial file, on a local disk or a shared filesystem.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "storage/zarr/byte_buffer.h"

namespace wavebake {

// Writes `data` to a uniquely named temp file beside `path` (".NAME.<random>.partial",
// which Zarr readers ignore), fsyncs it, renames it over `path` and fsyncs the
// directory. On any failure the temp file is removed and `path` is untouched.
// Errors name `path`; a full disk or quota (ENOSPC, EDQUOT) is ResourceExhausted
// ("No space left on device"), as it is for CreateDirectories.
absl::Status AtomicWriteFile(const std::filesystem::path& path, std::span<const std::byte> data);
// The same for a file written as consecutive parts (a header and the frames
// it describes), without first copying them into one buffer.
using FileParts = std::span<const std::span<const std::byte>>;
absl::Status AtomicWriteFileParts(const std::filesystem::path& path, FileParts parts);
// The same for text (CSV, JSON, an address file).
absl::Status AtomicWriteText(const std::filesystem::path& path, std::string_view text);

// Whether `name` (a file name, no directory) is one of AtomicWriteFile's temp
// names: what a writer that died, or one still writing, leaves beside a file.
bool IsAtomicTempName(std::string_view name);

// Removes, under `dir` and its subdirectories, the temp files of AtomicWriteFile
// calls whose writer died between write and rename (a worker killed mid-task).
// Only for when no writer of `dir` is left: FINALIZE, which has a store's last
// word, so that a published store holds exactly its arrays.
absl::Status RemoveAbandonedTempFiles(const std::filesystem::path& dir);

// Reads a whole file. A missing file is NotFound (ZarrArray reads a missing
// chunk as the fill value); other failures are Internal, naming the path.
absl::StatusOr<std::vector<std::byte>> ReadFile(const std::filesystem::path& path);
// The same into `data`, resized to the file: a buffer reused file after file
// keeps its pages (storage/zarr/byte_buffer.h).
absl::Status ReadFileInto(const std::filesystem::path& path, ByteBuffer& data);
// Bytes [offset, offset + size) of a file into `data`, resized to `size`: a
// header without the rest. A file that ends first is OutOfRange.
absl::Status ReadFileRangeInto(const std::filesystem::path& path, uint64_t offset, size_t size,
                               ByteBuffer& data);

// Creates `dir` and its parents; existing directories are fine (concurrent
// workers create the same array directories).
absl::Status CreateDirectories(const std::filesystem::path& dir);

}  // namespace wavebake
