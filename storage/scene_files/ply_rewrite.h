#pragma once
// A PLY file walked in full, and rewritten, before assimp reads it. Debian's
// assimp PLY reader trusts what a file says: a header without end_header hung
// it; a second vertex element, or a face list longer than the face's index
// list, makes it write or read past buffers sized by the other count;
// binary data beginning with a line-end byte is misread, the reader taking
// it for one more line end after end_header (a binary triangle here came
// back without its UVs); an out-of-range index crashed its post-processing.
// So assimp never sees the user's bytes: only the subset of PLY a mesh needs
// passes, checked value by value, and assimp reads it back rewritten as
// plain ASCII PLY.
//
// Accepted: "ply", a format line (ascii / binary_little_endian /
// binary_big_endian 1.0), comment and obj_info lines, exactly one "vertex"
// element (scalar properties, x y z among them) and one "face" element
// (scalar properties and one integer list named vertex_indices or
// vertex_index), end_header; then every instance, inside the file, every
// value a finite number of its type (ASCII: one instance per line), every
// face of 3..255 indices, each below the vertex count. Names are plain
// identifiers (assimp would take a '\r' in one for a line end) and a header
// line is at most 1024 bytes, with at most 64 properties per element. The
// rewrite keeps every vertex property (floating-point ones as float, as
// assimp stores them) and each face's indices; face scalars are dropped,
// nothing here reads them.
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace wavebake {

// The checked file as ASCII PLY, or InvalidArgument saying what is wrong and
// where (a header line, or an element instance); the caller adds the name.
absl::StatusOr<std::string> RewritePly(std::string_view file);

}  // namespace wavebake
