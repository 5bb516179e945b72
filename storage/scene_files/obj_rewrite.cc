#include "storage/scene_files/obj_rewrite.h"

#include <array>
#include <charconv>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

constexpr double kMaxMagnitude = 1e38;  // below FLT_MAX, with room for assimp's rounding
constexpr size_t kMaxCorners = 255;

absl::Status ObjBad(const auto&... what) {
  return absl::InvalidArgumentError(absl::StrCat(what...));
}

// Debian's abseil has a string_view of its own.
absl::string_view A(std::string_view s) { return {s.data(), s.size()}; }

// A token quoted in a message, cut short: it is the client's own text.
std::string Quote(std::string_view w) {
  return absl::StrCat("'", A(w.substr(0, 32)), w.size() > 32 ? "...'" : "'");
}

// At most `limit` words: a longer line is refused whatever its rest says,
// and a 6 MB face line must not become 3 M views.
std::vector<std::string_view> Words(std::string_view line, size_t limit) {
  std::vector<std::string_view> words;
  size_t at = 0;
  while (at < line.size() && words.size() < limit) {
    const size_t start = line.find_first_not_of(" \t", at);
    if (start == std::string_view::npos) break;
    const size_t end = std::min(line.find_first_of(" \t", start), line.size());
    words.push_back(line.substr(start, end - start));
    at = end;
  }
  return words;
}

absl::StatusOr<double> Number(std::string_view w) {
  std::string_view digits = w;
  if (digits.starts_with('+')) digits.remove_prefix(1);  // assimp reads it; from_chars not
  double v = 0;
  const auto [p, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (digits.empty() || ec != std::errc() || p != digits.data() + digits.size())
    return ObjBad(Quote(w), " is not a number");
  if (!(std::abs(v) <= kMaxMagnitude)) return ObjBad(Quote(w), " is not finite (or above 1e38)");
  return v;
}

// The element counts so far: vertices, texture coordinates, normals.
using Counts = std::array<int64_t, 3>;

// One corner's index `w` of kind `k` (0 v, 1 vt, 2 vn), as an absolute
// 1-based index of an element defined above.
absl::StatusOr<int64_t> Index(std::string_view w, int k, const Counts& counts) {
  static constexpr const char* kKinds[] = {"vertex", "texture coordinate", "normal"};
  int64_t i = 0;
  const auto [p, ec] = std::from_chars(w.data(), w.data() + w.size(), i);
  if (w.empty() || ec != std::errc() || p != w.data() + w.size())
    return ObjBad(kKinds[k], " index ", Quote(w), " is not an integer");
  const int64_t n = counts[k];
  const int64_t absolute = i < 0 ? n + 1 + i : i;
  if (i == 0 || absolute < 1 || absolute > n)
    return ObjBad(kKinds[k], " index ", i, " of ", n, " defined above it");
  return absolute;
}

// A face, line or point: its corners in one form, rewritten absolute.
absl::Status Corners(std::string_view keyword, const std::vector<std::string_view>& words,
                     size_t least, const Counts& counts, std::string* out) {
  const size_t corners = words.size() - 1;
  if (corners < least || corners > kMaxCorners)
    return ObjBad("'", A(keyword), "' with ", corners > kMaxCorners ? "more than " : "",
                  std::min(corners, kMaxCorners), " corners (", least, " to ", kMaxCorners,
                  " are read)");
  absl::StrAppend(out, A(keyword));
  int form = -1;  // bit k: index kind k present
  for (size_t c = 1; c < words.size(); ++c) {
    std::string_view w = words[c];
    std::array<std::string_view, 3> parts{};
    int slashes = 0, present = 0;
    for (int k = 0; k < 3; ++k) {
      const size_t slash = w.find('/');
      parts[k] = w.substr(0, slash);
      if (!parts[k].empty()) present |= 1 << k;
      if (slash == std::string_view::npos) break;
      ++slashes;
      w.remove_prefix(slash + 1);
      if (k == 2) return ObjBad("corner ", Quote(words[c]), " has more than three indices");
    }
    if (!(present & 1) || (slashes == 2 && !(present & 4)) || (slashes == 1 && !(present & 2)))
      return ObjBad("corner ", Quote(words[c]), " is not v, v/vt, v//vn or v/vt/vn");
    if (form >= 0 && present != form)
      return ObjBad("corner ", Quote(words[c]), " is not in the form of the face's first corner");
    form = present;
    out->push_back(' ');
    for (int k = 0; k < 3; ++k) {
      if (k == 2 && (present & 4) && !(present & 2)) out->push_back('/');  // v//vn
      if (!(present & (1 << k))) continue;
      absl::StatusOr<int64_t> index = Index(parts[k], k, counts);
      if (!index.ok()) return index.status();
      if (k > 0) out->push_back('/');
      absl::StrAppend(out, *index);
    }
  }
  out->push_back('\n');
  return absl::OkStatus();
}

// v, vt, vn: the numbers checked and written back as spelled.
absl::Status Numbers(std::string_view keyword, const std::vector<std::string_view>& words,
                     std::string* out) {
  const size_t n = words.size() - 1;
  const bool ok = keyword == "v"    ? (n == 3 || n == 4 || n == 6)
                  : keyword == "vt" ? (n == 2 || n == 3)
                                    : n == 3;
  if (!ok) {
    return ObjBad("'", A(keyword), "' with ", n, " numbers (",
                  keyword == "v"    ? "3, 4 or 6"
                  : keyword == "vt" ? "2 or 3"
                                    : "3",
                  " are read)");
  }
  std::array<double, 6> v{};
  for (size_t k = 0; k < n; ++k) {
    absl::StatusOr<double> x = Number(words[k + 1]);
    if (!x.ok()) return x.status();
    v[k] = *x;
  }
  if (keyword == "v" && n == 4) {  // homogeneous: assimp divides x, y, z by w
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(v[k]) <= kMaxMagnitude * std::abs(v[3])))
        return ObjBad("'v' with w ", A(words[4]), ": x/w, y/w, z/w must be finite below 1e38");
  }
  absl::StrAppend(out, A(keyword));
  for (size_t k = 1; k < words.size(); ++k) absl::StrAppend(out, " ", A(words[k]));
  out->push_back('\n');
  return absl::OkStatus();
}

absl::Status Statement(std::string_view line, Counts& counts, std::string* out) {
  for (const char c : line) {
    if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
      return ObjBad("a control byte (", static_cast<int>(static_cast<unsigned char>(c)), ")");
  }
  // A comment: a word starting with '#' and the rest of the line ("mat#2"
  // stays a name).
  for (size_t hash = line.find('#'); hash != std::string_view::npos;
       hash = line.find('#', hash + 1)) {
    if (hash == 0 || line[hash - 1] == ' ' || line[hash - 1] == '\t') {
      line = line.substr(0, hash);
      break;
    }
  }
  const std::vector<std::string_view> words = Words(line, kMaxCorners + 2);
  if (words.empty()) return absl::OkStatus();
  const std::string_view rest = line.substr(line.find_first_not_of(" \t"));
  const std::string_view trimmed = rest.substr(0, rest.find_last_not_of(" \t") + 1);
  if (trimmed.ends_with('\\')) return ObjBad("a '\\' line continuation (not read)");
  const std::string_view k = words[0];
  if (k == "v" || k == "vt" || k == "vn") {
    if (absl::Status s = Numbers(k, words, out); !s.ok()) return s;
    ++counts[k == "v" ? 0 : k == "vt" ? 1 : 2];
    return absl::OkStatus();
  }
  if (k == "f") return Corners(k, words, 3, counts, out);
  if (k == "l") return Corners(k, words, 2, counts, out);
  if (k == "p") return Corners(k, words, 1, counts, out);
  if (k == "o" || k == "g" || k == "s" || k == "usemtl" || k == "mtllib") {
    if (k == "s" && words.size() != 2) return ObjBad("'s' takes one group (a number or off)");
    if ((k == "o" || k == "usemtl" || k == "mtllib") && words.size() < 2)
      return ObjBad("'", A(k), "' without a name");
    // The names as written, spaces inside them included.
    absl::StrAppend(out, A(trimmed), "\n");
    return absl::OkStatus();
  }
  return ObjBad(Quote(k),
                " statements are not read (v, vt, vn, f, l, p, o, g, s, usemtl and mtllib are)");
}

}  // namespace

absl::StatusOr<std::string> RewriteObj(std::string_view file) {
  std::string out;
  out.reserve(file.size());
  Counts counts{};
  size_t number = 0;
  for (size_t at = 0; at < file.size();) {
    const size_t end = std::min(file.find('\n', at), file.size());
    std::string_view line = file.substr(at, end - at);
    at = end + 1;
    ++number;
    if (line.ends_with('\r')) line.remove_suffix(1);
    if (absl::Status s = Statement(line, counts, &out); !s.ok())
      return ObjBad("OBJ line ", number, ": ", s.message());
  }
  return out;
}

}  // namespace wavebake
