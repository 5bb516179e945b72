#include "runtime/gpu/wavelet_tree_reader.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "absl/strings/str_cat.h"

namespace wavebake {
namespace {

using nlohmann::json;

constexpr char kFormat[] = "wavebake-wavelet-tree/2";
constexpr uint32_t kNoTree = 0xFFFFFFFFu;

absl::Status Bad(const std::string& field, const std::string& why) {
  return absl::InvalidArgumentError(absl::StrCat("header: ", field, ": ", why));
}

// An integer field of `j` in [lo, hi], named by `field` in errors.
absl::StatusOr<int64_t> IntField(const json& j, const std::string& key, const std::string& field,
                                 int64_t lo, int64_t hi) {
  if (!j.is_object() || !j.contains(key)) return Bad(field, "missing");
  const json& v = j.at(key);
  if (!v.is_number_integer()) return Bad(field, "not an integer");
  const int64_t x = v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)
                        ? INT64_MAX
                        : v.get<int64_t>();
  if (x < lo || x > hi) return Bad(field, absl::StrCat(x, " is not in [", lo, ", ", hi, "]"));
  return x;
}

// One array's entry: a plain file name in the directory, its texture shape,
// its element type and channels.
struct ArraySpec {
  std::string file;
  int64_t texels = 0, width = 0, height = 0, channels = 0;
};
absl::StatusOr<ArraySpec> ArrayField(const json& h, const std::string& key, const char* type,
                                     int channels, int64_t min_texels, int64_t max_texels) {
  if (!h.contains(key) || !h[key].is_object()) return Bad(key, "missing");
  const json& a = h[key];
  ArraySpec s;
  if (!a.contains("file") || !a["file"].is_string()) return Bad(key + ".file", "missing");
  s.file = a["file"].get<std::string>();
  if (s.file.empty() || s.file == "." || s.file == ".." ||
      s.file.find_first_of("/\\") != std::string::npos || s.file.find('\0') != std::string::npos)
    return Bad(key + ".file", "not a plain file name");
  if (!a.contains("type") || a["type"] != type)
    return Bad(key + ".type", absl::StrCat("not ", type));
  absl::StatusOr<int64_t> ch = IntField(a, "channels", key + ".channels", channels, channels);
  if (!ch.ok()) return ch.status();
  absl::StatusOr<int64_t> texels = IntField(a, "texels", key + ".texels", min_texels, max_texels);
  if (!texels.ok()) return texels.status();
  absl::StatusOr<int64_t> w = IntField(a, "width", key + ".width", 1, 16384);
  if (!w.ok()) return w.status();
  absl::StatusOr<int64_t> hgt = IntField(a, "height", key + ".height", 0, 1 << 20);
  if (!hgt.ok()) return hgt.status();
  if (*hgt != (*texels + *w - 1) / *w)
    return Bad(key + ".height",
               absl::StrCat(*hgt, " rows do not hold ", *texels, " texels of ", *w, " a row"));
  s.texels = *texels;
  s.width = *w;
  s.height = *hgt;
  s.channels = channels;
  return s;
}

absl::StatusOr<std::vector<uint8_t>> ReadAll(const std::filesystem::path& p, uint64_t expect,
                                             const std::string& field) {
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(p, ec);
  if (ec) return absl::NotFoundError(absl::StrCat(field, ": cannot read ", p.string()));
  if (size != expect)
    return absl::InvalidArgumentError(
        absl::StrCat(field, ": ", p.string(), " has ", size, " bytes, the header says ", expect));
  std::vector<uint8_t> bytes(size);
  std::ifstream in(p, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
    return absl::DataLossError(absl::StrCat(field, ": cannot read ", p.string()));
  return bytes;
}

struct Header {
  int width = 0, height = 0, n = 0, levels = 0, step_bias = 0;
  int64_t sampled = 0, units = 0;
  std::vector<int> bits, record_units;
  ArraySpec line, blocks, cells;
};

// Units of a record as the header's "record" convention sizes it.
int UnitsOf(int level, int levels, int bits) {
  int b = 3 * bits;
  if (level < levels - 1) b += 4;  // child mask
  if (level < levels - 2) b += 1;  // jump flag
  return (b + 3) / 4;
}

absl::StatusOr<Header> CheckHeader(const json& h) {
  if (!h.is_object()) return Bad("header", "not a JSON object");
  if (!h.contains("format") || h["format"] != kFormat)
    return Bad("format", "not " + std::string(kFormat));
  Header r;
  absl::StatusOr<int64_t> w = IntField(h, "width", "width", 1, 65536);
  if (!w.ok()) return w.status();
  absl::StatusOr<int64_t> hh = IntField(h, "height", "height", 1, 65536);
  if (!hh.ok()) return hh.status();
  // Cells' A holds 1 + a rank as a float32: exact below 2^24.
  if (*w * *hh > (int64_t{1} << 24)) return Bad("width", "width × height exceeds 2^24 cells");
  absl::StatusOr<int64_t> nn = IntField(h, "light_res", "light_res", 2, 256);
  if (!nn.ok()) return nn.status();
  if (!std::has_single_bit(static_cast<uint64_t>(*nn)))
    return Bad("light_res", "not a power of two");
  absl::StatusOr<int64_t> lv = IntField(h, "levels", "levels", 1, 8);
  if (!lv.ok()) return lv.status();
  if ((int64_t{1} << *lv) != *nn) return Bad("levels", "is not log2(light_res)");
  absl::StatusOr<int64_t> sampled = IntField(h, "sampled", "sampled", 0, *w * *hh);
  if (!sampled.ok()) return sampled.status();
  absl::StatusOr<int64_t> bias = IntField(h, "step_bias", "step_bias", -96, 126);
  if (!bias.ok()) return bias.status();
  r.width = static_cast<int>(*w);
  r.height = static_cast<int>(*hh);
  r.n = static_cast<int>(*nn);
  r.levels = static_cast<int>(*lv);
  r.sampled = *sampled;
  r.step_bias = static_cast<int>(*bias);
  for (const char* key : {"code_bits", "record_units"}) {
    if (!h.contains(key) || !h[key].is_array()) return Bad(key, "missing");
    if (static_cast<int64_t>(h[key].size()) != *lv)
      return Bad(key, absl::StrCat(h[key].size(), " values, not one per level"));
  }
  for (int l = 0; l < r.levels; ++l) {
    const std::string at = absl::StrCat("[", l, "]");
    const json& b = h["code_bits"][l];
    if (!b.is_number_integer() || b.get<int64_t>() < 2 || b.get<int64_t>() > 9)
      return Bad("code_bits" + at, "not an integer in [2, 9]");
    r.bits.push_back(b.get<int>());
    const json& u = h["record_units"][l];
    if (!u.is_number_integer() || u.get<int64_t>() != UnitsOf(l, r.levels, r.bits[l]))
      return Bad("record_units" + at, absl::StrCat("is not ", UnitsOf(l, r.levels, r.bits[l]),
                                                   " for ", r.bits[l], "-bit codes"));
    r.record_units.push_back(u.get<int>());
  }
  if (!h.contains("line") || !h["line"].is_object()) return Bad("line", "missing");
  absl::StatusOr<int64_t> units =
      IntField(h["line"], "units", "line.units", 0, (int64_t{1} << 31) - 1);
  if (!units.ok()) return units.status();
  r.units = *units;
  // Whole texels of units and a spare one: a reader may fetch two at a time.
  absl::StatusOr<ArraySpec> line =
      ArrayField(h, "line", "uint8", 4, (*units + 7) / 8 + 1, int64_t{1} << 31);
  if (!line.ok()) return line.status();
  absl::StatusOr<ArraySpec> blocks =
      ArrayField(h, "blocks", "uint32", 2, 6 * *sampled, 6 * *sampled);
  if (!blocks.ok()) return blocks.status();
  absl::StatusOr<ArraySpec> cells = ArrayField(h, "cells", "float32", 4, *w * *hh, *w * *hh);
  if (!cells.ok()) return cells.status();
  if (cells->width != *w) return Bad("cells.width", "differs from width");
  r.line = *line;
  r.blocks = *blocks;
  r.cells = *cells;
  return r;
}

uint64_t BytesOf(const ArraySpec& a, int bytes_per_channel) {
  return uint64_t(a.width) * uint64_t(a.height) * uint64_t(a.channels) *
         uint64_t(bytes_per_channel);
}

}  // namespace

absl::StatusOr<WaveletTreeReader> WaveletTreeReader::Open(const std::filesystem::path& dir) {
  std::ifstream in(dir / "header.json");
  if (!in)
    return absl::NotFoundError(
        absl::StrCat("header: cannot read ", (dir / "header.json").string()));
  json h = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (h.is_discarded()) return Bad("header", "not valid JSON");
  absl::StatusOr<Header> s = CheckHeader(h);
  if (!s.ok()) return s.status();
  absl::StatusOr<std::vector<uint8_t>> line =
      ReadAll(dir / s->line.file, BytesOf(s->line, 1), "line");
  if (!line.ok()) return line.status();
  absl::StatusOr<std::vector<uint8_t>> blocks =
      ReadAll(dir / s->blocks.file, BytesOf(s->blocks, 4), "blocks");
  if (!blocks.ok()) return blocks.status();
  absl::StatusOr<std::vector<uint8_t>> cells =
      ReadAll(dir / s->cells.file, BytesOf(s->cells, 4), "cells");
  if (!cells.ok()) return cells.status();
  return Parse(h, *std::move(line), *std::move(blocks), *std::move(cells));
}

absl::StatusOr<WaveletTreeReader> WaveletTreeReader::Parse(const json& header,
                                                           std::vector<uint8_t> line,
                                                           std::vector<uint8_t> blocks,
                                                           std::vector<uint8_t> cells) {
  absl::StatusOr<Header> s = CheckHeader(header);
  if (!s.ok()) return s.status();
  if (line.size() != BytesOf(s->line, 1)) return Bad("line", "size differs from its shape");
  if (blocks.size() != BytesOf(s->blocks, 4)) return Bad("blocks", "size differs from its shape");
  if (cells.size() != BytesOf(s->cells, 4)) return Bad("cells", "size differs from its shape");
  WaveletTreeReader r;
  r.width_ = s->width;
  r.height_ = s->height;
  r.n_ = s->n;
  r.levels_ = s->levels;
  r.step_bias_ = s->step_bias;
  r.sampled_ = s->sampled;
  r.units_ = s->units;
  r.bits_ = s->bits;
  r.record_units_ = s->record_units;
  r.line_ = std::move(line);
  auto word = [](const std::vector<uint8_t>& v, size_t i) {
    return uint32_t(v[4 * i]) | uint32_t(v[4 * i + 1]) << 8 | uint32_t(v[4 * i + 2]) << 16 |
           uint32_t(v[4 * i + 3]) << 24;
  };
  r.blocks_.resize(blocks.size() / 4);
  for (size_t i = 0; i < r.blocks_.size(); ++i) r.blocks_[i] = word(blocks, i);
  r.cells_.resize(cells.size() / 4);
  for (size_t i = 0; i < r.cells_.size(); ++i) r.cells_[i] = std::bit_cast<float>(word(cells, i));
  // Padding: units past `units` are zero.
  for (int64_t u = r.units_; u < int64_t(r.line_.size()) * 2; ++u)
    if (r.Field(u, 4) != 0)
      return Bad("line", absl::StrCat("unit ", u, " past the trees is not zero"));
  // Cells: A is 0 or 1 + the running rank of sampled cells.
  int64_t rank = 0;
  for (int64_t c = 0; c < int64_t{r.width_} * r.height_; ++c) {
    const float a = r.cells_[4 * c + 3];
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(r.cells_[4 * c + k]))
        return Bad("cells", absl::StrCat("cell ", c, ": albedo not finite"));
    if (a == 0) continue;
    if (a != static_cast<float>(1 + rank))
      return Bad("cells", absl::StrCat("cell ", c, ": A is ", a, ", not 0 or ", 1 + rank));
    ++rank;
  }
  if (rank != r.sampled_)
    return Bad("cells", absl::StrCat(rank, " sampled cells, the header says ", r.sampled_));
  // Blocks: finite scaling coefficients; trees in block order, back to back.
  const int64_t nblocks = 6 * r.sampled_;
  r.tree_end_.assign(nblocks, 0);
  int64_t expect = 0, last = -1;
  for (int64_t b = 0; b < nblocks; ++b) {
    const uint32_t start = r.blocks_[2 * b];
    if (!std::isfinite(std::bit_cast<float>(r.blocks_[2 * b + 1])))
      return Bad("blocks", absl::StrCat("block ", b, " has a non-finite scaling coefficient"));
    if (start == kNoTree) continue;
    if (start != expect)
      return Bad("blocks", absl::StrCat("block ", b, " starts at unit ", start, ", not ", expect,
                                        " where the previous tree ends"));
    last = b;
    int64_t end = 0;
    if (absl::Status st = r.Walk(b, r.units_, nullptr, nullptr, &end); !st.ok()) return st;
    r.tree_end_[b] = end;
    expect = end;
  }
  if (last >= 0 && expect != r.units_)
    return Bad("line", absl::StrCat("the last tree ends at unit ", expect, ", not at ", r.units_));
  if (last < 0 && r.units_ != 0) return Bad("line", "units but no tree");
  return r;
}

uint64_t WaveletTreeReader::Field(int64_t unit, int bits) const {
  // Bits 4·unit .. 4·unit + bits − 1 of the little-endian stream.
  uint64_t v = 0;
  for (int k = 0; k < (bits + 3) / 4; ++k) {
    const int64_t u = unit + k;
    const uint8_t byte = line_[size_t(u / 2)];
    v |= uint64_t((u & 1) ? byte >> 4 : byte & 15) << (4 * k);
  }
  return bits >= 64 ? v : v & ((uint64_t{1} << bits) - 1);
}

absl::Status WaveletTreeReader::Walk(int64_t b, int64_t limit, float* row,
                                     std::vector<float>* steps, int64_t* end,
                                     uint8_t* present) const {
  const int64_t cell_block = b;
  auto bad = [&](int64_t u, const std::string& why) {
    return absl::InvalidArgumentError(absl::StrCat("line: tree of block ", cell_block, " (face ",
                                                   b % 6, "), unit ", u, ": ", why));
  };
  int64_t u = blocks_[2 * b];
  if (u + 2 * levels_ > limit) return bad(u, "the step codes run past the line");
  std::vector<float> step(levels_);
  for (int l = 0; l < levels_; ++l) {
    const int code = static_cast<int>(Field(u + 2 * l, 8));
    step[l] = code == 0
                  ? 0.0f
                  : static_cast<float>(std::ldexp(1.0 + (code % 8) / 8.0, code / 8 - step_bias_));
  }
  if (steps) *steps = step;
  u += 2 * levels_;
  // Depth first, recursively: a node of `level` at unit u.
  struct Walker {
    const WaveletTreeReader& r;
    const std::vector<float>& step;
    float* row;
    uint8_t* present;
    int64_t limit;
    decltype(bad)& fail;
    absl::Status Node(int level, int sx, int sy, int64_t& u) {
      const int units = r.record_units_[level], b = r.bits_[level];
      if (u + units > limit) return fail(u, "the tree runs past its end");
      const uint64_t rec = r.Field(u, 4 * units);
      const int64_t at = u;
      u += units;
      const int half = 1 << level;
      for (int t = 0; t < 3; ++t) {
        const int code = static_cast<int>((rec >> (t * b)) & ((1u << b) - 1));
        if (code == 0) return fail(at, "a code outside the window");
        const int x = t == 1 ? sx : half + sx;
        const int y = t == 0 ? sy : half + sy;
        if (row) row[size_t(y) * r.n_ + x] = float(code - (1 << (b - 1))) * step[level];
        if (present) present[size_t(y) * r.n_ + x] = 1;
      }
      int used = 3 * b;
      uint32_t mask = 0;
      bool jump = false;
      if (level < r.levels_ - 1) mask = uint32_t(rec >> used) & 15u, used += 4;
      if (level < r.levels_ - 2) jump = ((rec >> used) & 1u) != 0, used += 1;
      if ((rec >> used) != 0) return fail(at, "bits set past the record's fields");
      int64_t target = 0;
      if (jump) {
        if (level == 0) return fail(at, "a jump at the root");
        if (mask == 0) return fail(at, "a jump on a node without children");
        if (u + 4 > limit) return fail(u, "the jump runs past the tree's end");
        target = at + static_cast<int64_t>(r.Field(u, 16));
        u += 4;
      }
      for (int k = 0; k < 4; ++k) {
        if (!(mask & (1u << k))) continue;
        if (absl::Status s = Node(level + 1, 2 * sx + (k & 1), 2 * sy + (k >> 1), u); !s.ok())
          return s;
      }
      if (jump && target != u)
        return fail(at,
                    absl::StrCat("the jump lands at unit ", target, ", its subtree ends at ", u));
      return absl::OkStatus();
    }
  } walker{*this, step, row, present, limit, bad};
  if (absl::Status s = walker.Node(0, 0, 0, u); !s.ok()) return s;
  if (end) *end = u;
  return absl::OkStatus();
}

absl::Status WaveletTreeReader::DecodeRow(int cell, int face, std::span<float> row,
                                          std::vector<float>* steps,
                                          std::vector<uint8_t>* present) const {
  if (row.size() != size_t(n_) * n_) return absl::InvalidArgumentError("row: not N² floats");
  if (cell < 0 || cell >= width_ * height_ || !sampled(cell))
    return absl::InvalidArgumentError(absl::StrCat("cell: ", cell, " is not a sampled cell"));
  std::fill(row.begin(), row.end(), 0.0f);
  if (present) {
    present->assign(row.size(), 0);
    (*present)[0] = 1;
  }
  const int64_t b = 6 * (static_cast<int64_t>(cells_[4 * size_t(cell) + 3]) - 1) + face;
  row[0] = std::bit_cast<float>(blocks_[2 * b + 1]);
  if (blocks_[2 * b] == kNoTree) {
    if (steps) steps->assign(levels_, 0.0f);
    return absl::OkStatus();
  }
  return Walk(b, tree_end_[b], row.data(), steps, nullptr, present ? present->data() : nullptr);
}

absl::StatusOr<std::vector<float>> WaveletTreeReader::Relight(std::span<const float> L,
                                                              std::vector<float>* magnitude) const {
  const size_t per_face = size_t(n_) * n_;
  if (L.size() != 3 * 6 * per_face)
    return absl::InvalidArgumentError("lighting: not 3·6N² coefficients of the trees' N");
  const size_t cells = size_t(width_) * height_;
  std::vector<float> out(3 * cells, std::numeric_limits<float>::quiet_NaN());
  std::vector<float> row(per_face);
  if (magnitude) magnitude->assign(3 * cells, std::numeric_limits<float>::quiet_NaN());
  for (size_t cell = 0; cell < cells; ++cell) {
    if (!sampled(int(cell))) continue;
    double b[3] = {0, 0, 0}, m[3] = {0, 0, 0};
    for (int face = 0; face < 6; ++face) {
      if (absl::Status s = DecodeRow(int(cell), face, row); !s.ok()) return s;
      const float* l = &L[3 * face * per_face];
      for (size_t j = 0; j < per_face; ++j) {
        if (row[j] == 0) continue;
        for (int c = 0; c < 3; ++c) {
          b[c] += double{row[j]} * l[3 * j + c];
          m[c] += std::fabs(double{row[j]} * l[3 * j + c]);
        }
      }
    }
    for (int c = 0; c < 3; ++c) {
      out[3 * cell + c] = float(b[c] * cells_[4 * cell + c]);
      if (magnitude) (*magnitude)[3 * cell + c] = float(m[c] * cells_[4 * cell + c]);
    }
  }
  return out;
}

}  // namespace wavebake
