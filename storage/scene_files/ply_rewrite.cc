#include "storage/scene_files/ply_rewrite.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "absl/strings/str_cat.h"
#include "storage/scene_files/ply_header.h"

namespace wavebake {
namespace {

using ply::Header;
using ply::Property;
using ply::Type;

absl::Status Bad(const auto&... what) { return absl::InvalidArgumentError(absl::StrCat(what...)); }

// A value read from the body: integers exactly, floats as doubles.
struct Value {
  int64_t i = 0;
  double f = 0;
};

// The body's values, one instance at a time, in either encoding.
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

// One instance per line; values are read one at a time, so a line costs
// what it is long and nothing more.
class AsciiBody {
 public:
  explicit AsciiBody(std::string_view text) : text_(text) {}
  bool BeginInstance() {
    if (at_ >= text_.size()) return false;
    const size_t end = std::min(text_.find('\n', at_), text_.size());
    line_ = text_.substr(at_, end - at_);
    at_ = end + 1;
    return true;
  }
  absl::StatusOr<Value> Next(const Type& t) {
    const std::string_view w = NextWord();
    if (w.empty()) return Bad("its line has too few values");
    Value v;
    const auto [p, ec] = t.kind == Type::kFloat
                             ? std::from_chars(w.data(), w.data() + w.size(), v.f)
                             : std::from_chars(w.data(), w.data() + w.size(), v.i);
    if (ec != std::errc() || p != w.data() + w.size())
      return Bad(ply::Quote(w), " is not a valid ", t.name);
    return v;
  }
  absl::Status EndInstance() {
    if (NextWord().empty()) return absl::OkStatus();
    return Bad("its line has more values than its properties");
  }
  absl::Status EndBody() const {
    const std::string_view rest = at_ < text_.size() ? text_.substr(at_) : "";
    if (rest.find_first_not_of(" \t\r\n") == std::string_view::npos) return absl::OkStatus();
    return Bad("PLY with lines after its last face");
  }

 private:
  std::string_view NextWord() {
    const size_t start = std::min(line_.find_first_not_of(" \t\r"), line_.size());
    const size_t end = std::min(line_.find_first_of(" \t\r", start), line_.size());
    const std::string_view w = line_.substr(start, end - start);
    line_.remove_prefix(end);
    return w;
  }

  std::string_view text_, line_;
  size_t at_ = 0;
};

// Floats must be finite floats: assimp keeps every value as a float.
absl::Status InRange(const Value& v, const Type& t) {
  if (t.kind == Type::kFloat) {
    if (std::abs(v.f) <= std::numeric_limits<float>::max()) return absl::OkStatus();  // not NaN
    return Bad("a value that is not a finite float");
  }
  const int bits = 8 * t.bytes;
  const int64_t lo = t.kind == Type::kSigned ? -(int64_t{1} << (bits - 1)) : 0;
  const int64_t hi =
      t.kind == Type::kSigned ? (int64_t{1} << (bits - 1)) - 1 : int64_t((uint64_t{1} << bits) - 1);
  if (v.i >= lo && v.i <= hi) return absl::OkStatus();
  return Bad("value ", v.i, " does not fit in a ", t.name);
}

absl::StatusOr<Value> Checked(auto& body, const Type& t) {
  absl::StatusOr<Value> v = body.Next(t);
  if (!v.ok()) return v.status();
  if (absl::Status s = InRange(*v, t); !s.ok()) return s;
  return v;
}

// Floats as floats: their shortest form never has more than 9 significant
// digits, so never the 20-digit fixed notation that assimp's integer-part
// parser (64 bits) would wrap.
void Append(std::string* out, const Value& v, const Type& t) {
  char buf[32];
  const auto r = t.kind == Type::kFloat ? std::to_chars(buf, buf + sizeof buf, float(v.f))
                                        : std::to_chars(buf, buf + sizeof buf, v.i);
  out->append(buf, r.ptr);
}

// One face: its scalars checked and dropped, its index list written back.
absl::Status Face(auto& body, const Header& h, std::string* out) {
  for (const Property& p : h.face.properties) {
    absl::StatusOr<Value> v = Checked(body, p.count ? *p.count : p.type);
    if (!v.ok()) return Bad("property '", p.name, "': ", v.status().message());
    if (!p.count) continue;
    if (v->i < 3 || v->i > 255) return Bad("a face of ", v->i, " indices (3 to 255 are read)");
    absl::StrAppend(out, v->i);
    for (int64_t k = 0; k < v->i; ++k) {
      absl::StatusOr<Value> index = Checked(body, p.type);
      if (!index.ok()) return Bad("property '", p.name, "': ", index.status().message());
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
    absl::StatusOr<Value> v = Checked(body, p.type);
    if (!v.ok()) return Bad("property '", p.name, "': ", v.status().message());
    if (k) out->push_back(' ');
    Append(out, *v, p.type);
  }
  out->push_back('\n');
  return absl::OkStatus();
}

// The header puts the vertex element first (ply::ParseHeader), and so does
// the body.
absl::Status Body(auto body, const Header& h, std::string* out) {
  for (const ply::Element* e : {&h.vertex, &h.face}) {
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
  absl::StatusOr<Header> h = ply::ParseHeader(file);
  if (!h.ok()) return h.status();
  std::string out = absl::StrCat("ply\nformat ascii 1.0\nelement vertex ", h->vertex.count, "\n");
  for (const Property& p : h->vertex.properties)
    absl::StrAppend(&out, "property ", p.type.kind == Type::kFloat ? "float" : p.type.name, " ",
                    p.name, "\n");
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
