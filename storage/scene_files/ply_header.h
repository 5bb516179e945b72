#pragma once
// The header of a PLY file as storage/scene_files/ply_rewrite.h accepts it: its format
// and the one vertex and one face element, checked line by line. Internal to
// the PLY rewrite.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "absl/status/statusor.h"

namespace wavebake::ply {

// One of PLY's value types (either of its two spellings).
struct Type {
  const char* name;  // the canonical spelling
  int bytes;
  enum Kind { kSigned, kUnsigned, kFloat } kind;
};

struct Property {
  std::string name;           // [A-Za-z0-9_]+
  Type type;                  // of the value, or of a list's items
  std::optional<Type> count;  // a list's count type: only the face's index list
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  bool declared = false;
};

struct Header {
  enum Format { kAscii, kLittle, kBig } format = kAscii;
  Element vertex{"vertex", 0, {}, false}, face{"face", 0, {}, false};
  size_t body = 0;  // offset of the first byte after the end_header line
};

// The header, or InvalidArgument naming the line and what is wrong with it.
absl::StatusOr<Header> ParseHeader(std::string_view file);

// At most this many bytes are quoted back in an error message.
std::string Quote(std::string_view bytes);

}  // namespace wavebake::ply
