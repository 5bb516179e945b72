#pragma once
// A check of an OpenEXR file's headers before OpenEXR reads them. OpenEXR
// (3.1) allocates what a header declares before reading it: an unknown
// attribute's declared size (Imf::OpaqueAttribute::readValueFrom), a preview
// image's width × height, the offset tables of the data window — so a
// 40-byte file can make it allocate 1.7 GB (found by tests/fuzz/exr). This
// walks every header as OpenEXR will (the file layout of OpenEXR's
// "OpenEXRFileLayout" document: magic, version, then per part the
// attributes "name\0type\0", int32 size, value, an empty name ending the
// header; multi-part files end the list with an empty header) and refuses
// what would make it allocate beyond the file: a value larger than the rest
// of the file, a known type whose declared size is not its own (OpenEXR
// reads such values by type, not by size, and would parse on from elsewhere
// than this walk), and a data window of more pixels than ExrPixelLimit.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "absl/status/status.h"

namespace wavebake {

// The most pixels an EXR image of a file of `file_bytes` may have: no
// compression stores a pixel in less than 1/1024 byte (deflate's bound is
// ~1/86 for 12-byte pixels), at least 2^20 for tiny files and at most 2^27
// (16384 × 8192, far beyond what a 256² cubemap can use).
int64_t ExrPixelLimit(size_t file_bytes);

// InvalidArgument "NAME: unreadable EXR: ..." naming the header and attribute.
absl::Status CheckExrHeaders(std::span<const std::byte> file, const std::string& name);

}  // namespace wavebake
