#pragma once
// One chunk ⇄ one zstd frame (DESIGN.md §3): the frame header carries the
// content size (numcodecs 0.11 rejects frames without it) and the frame ends
// with a content checksum, so a corrupted chunk is detected on read.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "storage/zarr/byte_buffer.h"

namespace wavebake {

inline constexpr int kDefaultZstdLevel = 1;

// A level's match finder with some of its settings replaced (zstd's advanced
// parameters; 0 keeps the level's own). A frame decodes the same whatever
// found its matches, so a store records only the level (.zarray "level").
struct ZstdSearch {
  int strategy = 0;  // ZSTD_strategy
  int min_match = 0;
  int chain_log = 0;
  int hash_log = 0;
  int search_log = 0;
};

// Compresses `src` as a single frame at `level`. Thread-safe (contexts come from a pool).
absl::StatusOr<std::vector<std::byte>> ZstdCompress(std::span<const std::byte> src,
                                                    int level = kDefaultZstdLevel);
// The same into `frame`, resized to the frame: a buffer reused chunk after
// chunk keeps its pages (storage/zarr/byte_buffer.h).
absl::Status ZstdCompressInto(std::span<const std::byte> src, int level, ByteBuffer& frame,
                              const ZstdSearch& search = {});

// Decompresses a buffer that must be exactly one frame whose header declares
// `expected_size` content bytes; the checksum is verified when the frame has
// one (frames written by other Zarr writers may not). Errors are DataLoss and
// name `source` (the chunk file). Thread-safe.
absl::StatusOr<std::vector<std::byte>> ZstdDecompress(std::span<const std::byte> frame,
                                                      size_t expected_size,
                                                      absl::string_view source);
// The same, into `out`, whose size is the expected content size.
absl::Status ZstdDecompressInto(std::span<const std::byte> frame, std::span<std::byte> out,
                                absl::string_view source);
// The content size a frame's header declares, to size its output before
// decompressing (DataLoss naming `source` if the header has none).
absl::StatusOr<uint64_t> ZstdFrameContentSize(std::span<const std::byte> frame,
                                              absl::string_view source);

}  // namespace wavebake
