#include "storage/scene_files/ply_header.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <unordered_set>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace wavebake::ply {
namespace {

constexpr std::array<std::pair<std::string_view, Type>, 16> kTypes{{
    {"char", {"char", 1, Type::kSigned}},
    {"int8", {"char", 1, Type::kSigned}},
    {"uchar", {"uchar", 1, Type::kUnsigned}},
    {"uint8", {"uchar", 1, Type::kUnsigned}},
    {"short", {"short", 2, Type::kSigned}},
    {"int16", {"short", 2, Type::kSigned}},
    {"ushort", {"ushort", 2, Type::kUnsigned}},
    {"uint16", {"ushort", 2, Type::kUnsigned}},
    {"int", {"int", 4, Type::kSigned}},
    {"int32", {"int", 4, Type::kSigned}},
    {"uint", {"uint", 4, Type::kUnsigned}},
    {"uint32", {"uint", 4, Type::kUnsigned}},
    {"float", {"float", 4, Type::kFloat}},
    {"float32", {"float", 4, Type::kFloat}},
    {"double", {"double", 8, Type::kFloat}},
    {"float64", {"double", 8, Type::kFloat}},
}};

// Bounds on what a header may hold, so that its checks cost what the file
// is long: real meshes have a few dozen properties and short lines.
constexpr size_t kMaxLine = 1024;
constexpr size_t kMaxProperties = 64;

std::optional<Type> TypeNamed(std::string_view name) {
  for (const auto& [spelling, type] : kTypes)
    if (spelling == name) return type;
  return std::nullopt;
}

// Names are written back into the header assimp reads, and assimp takes
// '\r', '\f' and '\0' for line ends and '\t' for a space: a name holding
// them could smuggle in a second element. Only plain identifiers pass.
bool PlainName(std::string_view name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::vector<std::string_view> Words(std::string_view line) {
  std::vector<std::string_view> words;
  for (size_t at = line.find_first_not_of(' '); at != std::string_view::npos;) {
    const size_t end = std::min(line.find(' ', at), line.size());
    words.push_back(line.substr(at, end - at));
    at = line.find_first_not_of(' ', end);
  }
  return words;
}

absl::Status Bad(int line, const auto&... what) {
  return absl::InvalidArgumentError(absl::StrCat("PLY header line ", line, ": ", what...));
}

absl::Status AddProperty(Element* e, const std::vector<std::string_view>& w, int line) {
  const bool list = w.size() == 5 && w[1] == "list";
  if (!list && w.size() != 3) return Bad(line, "a malformed property line");
  if (!PlainName(w.back()))
    return Bad(line, "property name ", Quote(w.back()), " (letters, digits and _ only)");
  Property p{std::string(w.back()), {}, std::nullopt};
  const std::optional<Type> type = TypeNamed(w[list ? 3 : 1]);
  if (!type) return Bad(line, "unknown type ", Quote(w[list ? 3 : 1]));
  p.type = *type;
  if (e->properties.size() >= kMaxProperties)
    return Bad(line, "more than ", kMaxProperties, " properties of element '", e->name, "'");
  if (list) {
    p.count = TypeNamed(w[2]);
    const bool indices = p.name == "vertex_indices" || p.name == "vertex_index";
    if (e->name != "face" || !indices)
      return Bad(line, "list property '", p.name, "' of element '", e->name,
                 "' (the only list read is the face's vertex_indices)");
    if (!p.count || p.count->kind == Type::kFloat || p.type.kind == Type::kFloat)
      return Bad(line, "the face's index list needs integer types");
  }
  for (const Property& q : e->properties) {
    if (q.name == p.name) return Bad(line, "property '", p.name, "' twice");
    if (list && q.count) return Bad(line, "a second face index list");
  }
  e->properties.push_back(std::move(p));
  return absl::OkStatus();
}

absl::Status AddElement(Header* h, const std::vector<std::string_view>& w, int line,
                        Element** current) {
  if (w.size() != 3) return Bad(line, "a malformed element line (element NAME COUNT)");
  *current = w[1] == "vertex" ? &h->vertex : w[1] == "face" ? &h->face : nullptr;
  if (*current == nullptr || (*current)->declared)
    return Bad(line, "not the one vertex or face element (only those are read)");
  if (*current == &h->face && !h->vertex.declared)
    return Bad(line, "the face element before the vertex element");
  const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), (*current)->count);
  if (ec != std::errc() || p != w[2].data() + w[2].size())
    return Bad(line, "element count ", Quote(w[2]), " is not a number");
  (*current)->declared = true;
  return absl::OkStatus();
}

absl::Status Finish(const Header& h) {
  for (const char* axis : {"x", "y", "z"}) {
    bool found = false;
    for (const Property& p : h.vertex.properties) found = found || p.name == axis;
    if (!found)
      return absl::InvalidArgumentError(
          absl::StrCat("PLY vertex element without property '", axis, "'"));
  }
  bool indices = false;
  for (const Property& p : h.face.properties) indices = indices || p.count.has_value();
  if (!h.face.declared || !indices || h.face.count == 0)
    return absl::InvalidArgumentError("PLY without a face element, its index list and a face");
  if (h.vertex.count > (uint64_t{1} << 31) - 1)
    return absl::InvalidArgumentError(
        absl::StrCat("PLY vertex count ", h.vertex.count, " (at most 2^31 - 1)"));
  return absl::OkStatus();
}

absl::Status Format(std::string_view text, Header* h) {
  const std::vector<std::string_view> w = Words(text);
  const std::string_view f = w.size() == 3 && w[0] == "format" && w[2] == "1.0" ? w[1] : "";
  if (f != "ascii" && f != "binary_little_endian" && f != "binary_big_endian")
    return Bad(2, "not a format line (ascii, binary_little_endian or binary_big_endian 1.0)");
  h->format = f == "ascii"               ? Header::kAscii
              : f == "binary_big_endian" ? Header::kBig
                                         : Header::kLittle;
  return absl::OkStatus();
}

}  // namespace

std::string Quote(std::string_view bytes) {
  const size_t n = std::min<size_t>(bytes.size(), 40);
  return absl::StrCat("'", absl::CEscape(absl::string_view(bytes.data(), n)),
                      n < bytes.size() ? "…'" : "'");
}

absl::StatusOr<Header> ParseHeader(std::string_view file) {
  if (file.find("\nend_header") == std::string_view::npos)
    return absl::InvalidArgumentError("a PLY header without its end_header line");
  Header h;
  Element* current = nullptr;
  size_t at = 0;
  for (int line = 1; at < file.size(); ++line) {
    const size_t end = std::min(file.find('\n', at), file.size());
    std::string_view text = file.substr(at, end - at);
    at = end + 1;
    if (text.size() > kMaxLine) return Bad(line, "longer than ", kMaxLine, " bytes");
    while (!text.empty() && (text.back() == '\r' || text.back() == ' ')) text.remove_suffix(1);
    const std::string_view key = text.substr(0, text.find(' '));
    absl::Status s;
    if (line == 1) {
      if (text != "ply") return absl::InvalidArgumentError("PLY header line 1 is not 'ply'");
    } else if (line == 2) {
      s = Format(text, &h);
    } else if (key == "comment" || key == "obj_info") {
    } else if (key == "element") {
      s = AddElement(&h, Words(text), line, &current);
    } else if (key == "property") {
      if (current == nullptr) return Bad(line, "a property before elements");
      s = AddProperty(current, Words(text), line);
    } else if (text == "end_header") {
      h.body = std::min(at, file.size());
      if (absl::Status f = Finish(h); !f.ok()) return f;
      return h;
    } else {
      return Bad(line, "not a header keyword");
    }
    if (!s.ok()) return s;
  }
  return absl::InvalidArgumentError("a PLY header without its end_header line");
}

}  // namespace wavebake::ply
