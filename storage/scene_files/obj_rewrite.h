#pragma once
// A Wavefront OBJ walked in full, and rewritten, before assimp reads it, as
// PLY is (storage/scene_files/ply_rewrite.h). assimp's post-processing triangulates a
// polygon in time quadratic in its corners (a single face line of 3 M
// indices would take days and ignore SIGTERM), and its reader trusts what
// a file says. So assimp never sees the user's bytes: only the subset of
// OBJ a mesh needs passes, checked statement by statement, and assimp reads
// it back rewritten.
//
// Accepted, one statement per line ('\n' or "\r\n"; blank lines and '#'
// comments dropped, no '\' continuation, no control bytes):
//   v x y z [w] | v x y z r g b    vertex (w non-zero; assimp divides by it)
//   vt u v [w]                     texture coordinate
//   vn x y z                       normal
//   f REF REF REF ...              3 to 255 corners
//   l REF REF ...  /  p REF ...    2 to 255 / 1 to 255 (kept as assimp keeps them)
//   o NAME, g [NAMES], s GROUP, usemtl NAME, mtllib FILES
// every number finite and at most 1e38 in magnitude (assimp keeps floats);
// REF is v, v/vt, v//vn or v/vt/vn, one form for all corners of a face,
// each index non-zero and naming an element defined above it: a negative
// index counts back from the last one (OBJ's relative form) and is
// rewritten as the absolute index it names. Faces above 255 corners are
// refused rather than triangulated here: a fan, the only linear
// triangulation, is wrong for a concave polygon, and no mesh this baker is
// for needs them (PLY has the same bound). Numbers are written back as the
// file spelled them, so assimp reads the same floats it read before.
#include <string>
#include <string_view>

#include "absl/status/statusor.h"

namespace wavebake {

// The checked file as OBJ, or InvalidArgument naming the line ("OBJ line
// 12: ...") and what is wrong; the caller adds the file's name.
absl::StatusOr<std::string> RewriteObj(std::string_view file);

}  // namespace wavebake
