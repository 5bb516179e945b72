// The OBJ check and rewrite alone (storage/scene_files/obj_rewrite.h), without assimp
// behind it (tests/fuzz/obj loads whole scenes). Properties beyond "no
// crash": a refusal is INVALID_ARGUMENT naming a line of the input; a
// rewrite is a fixed point (its own rewrite), has no more lines than the
// input, and every face in it has 3 to 255 corners with indices in range.
#include <charconv>

#include "storage/scene_files/obj_rewrite.h"
#include "tests/fuzz/fuzz_util.h"

namespace wavebake::fuzz {

std::vector<std::string> Seeds() {
  return {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
          "# c\r\nmtllib a b.mtl\r\no x\r\nv 1e-3\t+2 -3.5\r\nv 4 5 6 0.5\r\nv 7 8 9 1 0.5 0\r\n"
          "vt 0.25 0.75\nvn 0 0 1\ng a b\nusemtl m#2\ns off\nf -3/-1/1 2/1/-1 -1/1/1\n"
          "f 1//1 2//1 3//-1\nf 1/1 -2/1 3/1\nl 1 -1\np -3\n",
          "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n",
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1 2 3 1 2 3 1 2 3 1 2 3 1 2 3 1 2 3\n"};
}

}  // namespace wavebake::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using wavebake::fuzz::Require;
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const absl::StatusOr<std::string> out = wavebake::RewriteObj(in);
  size_t lines = 0;
  for (char c : in) lines += c == '\n';
  if (!out.ok()) {
    Require(absl::IsInvalidArgument(out.status()), "refusals are INVALID_ARGUMENT");
    const std::string m(out.status().message());
    Require(m.starts_with("OBJ line "), "a refusal names its line");
    size_t line = 0;
    std::from_chars(m.data() + 9, m.data() + m.size(), line);
    Require(line >= 1 && line <= lines + 1, "the line named is in the input");
    return 0;
  }
  size_t out_lines = 0;
  for (char c : *out) out_lines += c == '\n';
  Require(out_lines <= lines + 1, "no more lines than the input");
  Require(out->empty() || out->back() == '\n', "whole lines");
  const absl::StatusOr<std::string> again = wavebake::RewriteObj(*out);
  Require(again.ok() && *again == *out, "a rewrite is its own rewrite");
  // Faces: 3..255 corners, positive indices (the fixed point checked range).
  for (size_t at = 0; at < out->size();) {
    const size_t end = out->find('\n', at);
    const std::string_view line(out->data() + at, end - at);
    at = end + 1;
    if (!line.starts_with("f ")) continue;
    size_t corners = 0;
    for (char c : line) corners += c == ' ';
    Require(corners >= 3 && corners <= 255, "faces of 3 to 255 corners");
    Require(line.find('-') == std::string_view::npos, "indices written absolute");
  }
  return 0;
}
