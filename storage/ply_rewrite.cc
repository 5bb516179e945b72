#include "storage/ply_rewrite.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

// PLY's value types, by both of their spellings.
struct Type {
  const char* name;  // the canonical spelling, as written back
  int bytes;
  enum Kind { kSigned, kUnsigned, kFloat } kind;
};
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

std::optional<Type> TypeNamed(std::string_view name) {
  for (const auto& [spelling, type] : kTypes)
    if (spelling == name) return type;
  return std::nullopt;
}

struct Property {
  std::string name;
  Type type;
  std::optional<Type> count;  // set for the face's index list
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
  size_t body = 0;  // offset of the first byte after end_header's line
};

// The words of a line, split at any of `separators`.
std::vector<std::string_view> Words(std::string_view line, std::string_view separators) {
  std::vector<std::string_view> words;
  for (size_t at = line.find_first_not_of(separators); at != std::string_view::npos;) {
    const size_t end = std::min(line.find_first_of(separators, at), line.size());
    words.push_back(line.substr(at, end - at));
    at = line.find_first_not_of(separators, end);
  }
  return words;
}

absl::Status Bad(const auto&... what) { return absl::InvalidArgumentError(absl::StrCat(what...)); }

absl::Status AddProperty(Element* e, const std::vector<std::string_view>& w, int line) {
  const bool list = w.size() == 5 && w[1] == "list";
  if (!list && w.size() != 3) return Bad("PLY header line ", line, ": a malformed property");
  Property p{std::string(w.back()), {}, std::nullopt};
  const std::optional<Type> type = TypeNamed(w[list ? 3 : 1]);
  if (!type)
    return Bad("PLY header line ", line, ": unknown type '", std::string(w[list ? 3 : 1]), "'");
  p.type = *type;
  for (const Property& q : e->properties)
    if (q.name == p.name) return Bad("PLY header line ", line, ": property '", p.name, "' twice");
  if (list) {
    p.count = TypeNamed(w[2]);
    const bool indices = p.name == "vertex_indices" || p.name == "vertex_index";
    if (e->name != "face" || !indices)
      return Bad("PLY header line ", line, ": list property '", p.name, "' of element '", e->name,
                 "' (the only list read is the face's vertex_indices)");
    if (!p.count || p.count->kind == Type::kFloat || p.type.kind == Type::kFloat)
      return Bad("PLY header line ", line, ": the face's index list needs integer types");
    for (const Property& q : e->properties)
      if (q.count) return Bad("PLY header line ", line, ": a second face index list");
  }
  e->properties.push_back(std::move(p));
  return absl::OkStatus();
}

absl::Status Finish(const Header& h) {
  for (const char* axis : {"x", "y", "z"}) {
    bool found = false;
    for (const Property& p : h.vertex.properties) found = found || p.name == axis;
    if (!found) return Bad("PLY vertex element without property '", axis, "'");
  }
  bool indices = false;
  for (const Property& p : h.face.properties) indices = indices || p.count.has_value();
  if (!h.face.declared || !indices) return Bad("PLY without a face element and its index list");
  if (h.vertex.count > (uint64_t{1} << 31) - 1)
    return Bad("PLY vertex count ", h.vertex.count, " (at most 2^31 - 1)");
  return absl::OkStatus();
}

absl::StatusOr<Header> ParseHeader(std::string_view file) {
  if (file.find("\nend_header") == std::string_view::npos)
    return Bad("a PLY header without its end_header line");
  Header h;
  Element* current = nullptr;
  size_t at = 0;
  for (int line = 1; at < file.size(); ++line) {
    size_t end = file.find('\n', at);
    if (end == std::string_view::npos) break;
    std::string_view text = file.substr(at, end - at);
    at = end + 1;
    if (text.ends_with('\r')) text.remove_suffix(1);
    const std::vector<std::string_view> w = Words(text, " ");
    const std::string_view key = w.empty() ? "" : w[0];
    if (line == 1) {
      if (text != "ply") return Bad("PLY header line 1 is not 'ply'");
    } else if (line == 2) {
      const std::string_view f = w.size() == 3 && w[0] == "format" && w[2] == "1.0" ? w[1] : "";
      if (f != "ascii" && f != "binary_little_endian" && f != "binary_big_endian")
        return Bad(
            "PLY header line 2 is not a format line (ascii, binary_little_endian or "
            "binary_big_endian 1.0)");
      h.format = f == "ascii"               ? Header::kAscii
                 : f == "binary_big_endian" ? Header::kBig
                                            : Header::kLittle;
    } else if (key == "comment" || key == "obj_info") {
    } else if (key == "element") {
      current = w.size() != 3      ? nullptr
                : w[1] == "vertex" ? &h.vertex
                : w[1] == "face"   ? &h.face
                                   : nullptr;
      if (current == nullptr || current->declared)
        return Bad("PLY header line ", line,
                   ": not the one vertex or face element (only those are read)");
      const auto [p, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), current->count);
      if (ec != std::errc() || p != w[2].data() + w[2].size())
        return Bad("PLY header line ", line, ": element count '", std::string(w[2]),
                   "' is not a number");
      current->declared = true;
    } else if (key == "property") {
      if (current == nullptr) return Bad("PLY header line ", line, ": a property before elements");
      if (absl::Status s = AddProperty(current, w, line); !s.ok()) return s;
    } else if (text == "end_header") {
      h.body = at;
      if (absl::Status s = Finish(h); !s.ok()) return s;
      return h;
    } else {
      return Bad("PLY header line ", line, " is not a header keyword");
    }
  }
  return Bad("a PLY header without its end_header line");
}

// A value read from the body: integers exactly, floats as doubles.
struct Value {
  int64_t i = 0;
  double f = 0;
};

// Reads the values of one instance at a time, either encoding.
class BinaryBody {
 public:
  BinaryBody(std::string_view bytes, bool big) : bytes_(bytes), big_(big) {}
  bool BeginInstance() { return at_ < bytes_.size(); }
  absl::StatusOr<Value> Next(const Type& t) {
    if (bytes_.size() - at_ < size_t(t.bytes)) return Bad("the file ends inside it");
    std::array<unsigned char, 8> b{};
    std::memcpy(b.data(), bytes_.data() + at_, t.bytes);
    at_ += t.bytes;
    if (big_) std::reverse(b.begin(), b.begin() + t.bytes);
    uint64_t u = 0;
    for (int k = t.bytes - 1; k >= 0; --k) u = u << 8 | b[k];
    Value v;
    if (t.kind == Type::kFloat) {
      v.f = t.bytes == 4 ? double(std::bit_cast<float>(uint32_t(u))) : std::bit_cast<double>(u);
    } else if (t.kind == Type::kSigned) {
      const int shift = 64 - 8 * t.bytes;
      v.i = static_cast<int64_t>(u << shift) >> shift;  // sign-extended
    } else {
      v.i = static_cast<int64_t>(u);
    }
    return v;
  }
  absl::Status EndInstance() { return absl::OkStatus(); }
  absl::Status EndBody() const {
    if (at_ == bytes_.size()) return absl::OkStatus();
    return Bad("PLY with ", bytes_.size() - at_, " bytes after its last face");
  }

 private:
  std::string_view bytes_;
  size_t at_ = 0;
  bool big_;
};

class AsciiBody {
 public:
  explicit AsciiBody(std::string_view text) : text_(text) {}
  bool BeginInstance() {
    if (at_ >= text_.size()) return false;
    size_t end = text_.find('\n', at_);
    if (end == std::string_view::npos) end = text_.size();
    words_ = Words(text_.substr(at_, end - at_), " \t\r");
    at_ = end + 1;
    next_ = 0;
    return true;
  }
  absl::StatusOr<Value> Next(const Type& t) {
    if (next_ >= words_.size()) return Bad("its line has too few values");
    const std::string_view w = words_[next_++];
    Value v;
    const auto [p, ec] = t.kind == Type::kFloat
                             ? std::from_chars(w.data(), w.data() + w.size(), v.f)
                             : std::from_chars(w.data(), w.data() + w.size(), v.i);
    if (ec != std::errc() || p != w.data() + w.size())
      return Bad("'", absl::CEscape(absl::string_view(w.data(), w.size())), "' is not a ", t.name);
    return v;
  }
  absl::Status EndInstance() {
    if (next_ == words_.size()) return absl::OkStatus();
    return Bad("its line has ", words_.size() - next_, " values too many");
  }
  absl::Status EndBody() const {
    const std::string_view rest = at_ < text_.size() ? text_.substr(at_) : "";
    if (Words(rest, " \t\r\n").empty()) return absl::OkStatus();
    return Bad("PLY with lines after its last face");
  }

 private:
  std::string_view text_;
  size_t at_ = 0;
  std::vector<std::string_view> words_;
  size_t next_ = 0;
};

absl::Status InRange(const Value& v, const Type& t) {
  if (t.kind == Type::kFloat) {
    const double max =
        t.bytes == 4 ? std::numeric_limits<float>::max() : std::numeric_limits<double>::max();
    if (std::abs(v.f) <= max) return absl::OkStatus();  // NaN fails too
    return Bad("a value that is not a finite ", t.name);
  }
  const int bits = 8 * t.bytes;
  const int64_t lo = t.kind == Type::kSigned ? -(int64_t{1} << (bits - 1)) : 0;
  const int64_t hi =
      t.kind == Type::kSigned ? (int64_t{1} << (bits - 1)) - 1 : int64_t((uint64_t{1} << bits) - 1);
  if (v.i >= lo && v.i <= hi) return absl::OkStatus();
  return Bad("value ", v.i, " does not fit a ", t.name);
}

void Append(std::string* out, const Value& v, const Type& t) {
  char buf[32];
  const auto r = t.kind != Type::kFloat ? std::to_chars(buf, buf + sizeof buf, v.i)
                 : t.bytes == 4         ? std::to_chars(buf, buf + sizeof buf, float(v.f))
                                        : std::to_chars(buf, buf + sizeof buf, v.f);
  out->append(buf, r.ptr);
}

// One face: its scalars skipped, its index list checked and written back.
absl::Status Face(auto& body, const Header& h, std::string* out) {
  for (const Property& p : h.face.properties) {
    absl::StatusOr<Value> v = body.Next(p.count ? *p.count : p.type);
    if (!v.ok()) return v.status();
    if (absl::Status s = InRange(*v, p.count ? *p.count : p.type); !s.ok()) return s;
    if (!p.count) continue;
    if (v->i < 3 || v->i > 255) return Bad("a face of ", v->i, " indices (3 to 255 are read)");
    absl::StrAppend(out, v->i);
    for (int64_t k = 0; k < v->i; ++k) {
      absl::StatusOr<Value> index = body.Next(p.type);
      if (!index.ok()) return index.status();
      if (index->i < 0 || uint64_t(index->i) >= h.vertex.count)
        return Bad("vertex index ", index->i, " of ", h.vertex.count, " vertices");
      absl::StrAppend(out, " ", index->i);
    }
  }
  out->push_back('\n');
  return absl::OkStatus();
}

absl::Status Vertex(auto& body, const Header& h, std::string* out) {
  for (size_t k = 0; k < h.vertex.properties.size(); ++k) {
    const Property& p = h.vertex.properties[k];
    absl::StatusOr<Value> v = body.Next(p.type);
    if (!v.ok()) return v.status();
    if (absl::Status s = InRange(*v, p.type); !s.ok())
      return Bad("property '", p.name, "': ", s.message());
    if (k) out->push_back(' ');
    Append(out, *v, p.type);
  }
  out->push_back('\n');
  return absl::OkStatus();
}

absl::Status Body(auto body, const Header& h, std::string* out) {
  for (const Element* e : {&h.vertex, &h.face}) {
    for (uint64_t n = 0; n < e->count; ++n) {
      if (!body.BeginInstance()) return Bad("PLY ends at ", e->name, " ", n, " of ", e->count);
      absl::Status s = e == &h.vertex ? Vertex(body, h, out) : Face(body, h, out);
      if (s.ok()) s = body.EndInstance();
      if (!s.ok()) return Bad("PLY ", e->name, " ", n, ": ", s.message());
    }
  }
  return body.EndBody();
}

}  // namespace

absl::StatusOr<std::string> RewritePly(std::string_view file) {
  absl::StatusOr<Header> h = ParseHeader(file);
  if (!h.ok()) return h.status();
  std::string out = absl::StrCat("ply\nformat ascii 1.0\nelement vertex ", h->vertex.count, "\n");
  for (const Property& p : h->vertex.properties)
    absl::StrAppend(&out, "property ", p.type.name, " ", p.name, "\n");
  absl::StrAppend(&out, "element face ", h->face.count,
                  "\nproperty list uchar int vertex_indices\nend_header\n");
  const std::string_view body = file.substr(h->body);
  const absl::Status s = h->format == Header::kAscii
                             ? Body(AsciiBody(body), *h, &out)
                             : Body(BinaryBody(body, h->format == Header::kBig), *h, &out);
  if (!s.ok()) return s;
  return out;
}

}  // namespace wavebake
