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
// its element type; returns the byte size it must have.
struct ArraySpec {
  std::string file;
  int64_t texels = 0, width = 0, height = 0;
};
absl::StatusOr<ArraySpec> ArrayField(const json& h, const std::string& key, const char* type,
                                     int64_t texels_expected) {
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
  absl::StatusOr<int64_t> ch = IntField(a, "channels", key + ".channels", 4, 4);
  if (!ch.ok()) return ch.status();
  absl::StatusOr<int64_t> texels = IntField(a, "texels", key + ".texels", 0, int64_t{1} << 31);
  if (!texels.ok()) return texels.status();
  if (texels_expected >= 0 && *texels != texels_expected)
    return Bad(key + ".texels", absl::StrCat(*texels, " != ", texels_expected));
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

struct Shapes {
  ArraySpec line, blocks, cells;
  int bits = 0;
};

absl::StatusOr<Shapes> CheckHeader(const json& h, int& width, int& height, int& n, int& levels,
                                   int& bits, int& bias) {
  if (!h.is_object()) return Bad("header", "not a JSON object");
  if (!h.contains("format") || h["format"] != "wavebake-wavelet-tree/1")
    return Bad("format", "not wavebake-wavelet-tree/1");
  absl::StatusOr<int64_t> w = IntField(h, "width", "width", 1, 65536);
  if (!w.ok()) return w.status();
  absl::StatusOr<int64_t> hh = IntField(h, "height", "height", 1, 65536);
  if (!hh.ok()) return hh.status();
  if (*w * *hh > (int64_t{1} << 26)) return Bad("width", "width × height exceeds 2^26 cells");
  absl::StatusOr<int64_t> nn = IntField(h, "light_res", "light_res", 2, 256);
  if (!nn.ok()) return nn.status();
  if (!std::has_single_bit(static_cast<uint64_t>(*nn)))
    return Bad("light_res", "not a power of two");
  absl::StatusOr<int64_t> lv = IntField(h, "levels", "levels", 1, 8);
  if (!lv.ok()) return lv.status();
  if ((int64_t{1} << *lv) != *nn) return Bad("levels", "is not log2(light_res)");
  absl::StatusOr<int64_t> b = IntField(h, "bits", "bits", 8, 16);
  if (!b.ok()) return b.status();
  if (*b != 8 && *b != 16) return Bad("bits", "not 8 or 16");
  absl::StatusOr<int64_t> bi = IntField(h, "bias", "bias", 0, 65535);
  if (!bi.ok()) return bi.status();
  if (*bi != (int64_t{1} << (*b - 1))) return Bad("bias", "is not 2^(bits-1)");
  width = static_cast<int>(*w);
  height = static_cast<int>(*hh);
  n = static_cast<int>(*nn);
  levels = static_cast<int>(*lv);
  bits = static_cast<int>(*b);
  bias = static_cast<int>(*bi);
  Shapes s;
  s.bits = bits;
  absl::StatusOr<ArraySpec> line = ArrayField(h, "line", bits == 8 ? "uint8" : "uint16", -1);
  if (!line.ok()) return line.status();
  absl::StatusOr<ArraySpec> blocks = ArrayField(h, "blocks", "uint32", *w * *hh * 6);
  if (!blocks.ok()) return blocks.status();
  absl::StatusOr<ArraySpec> cells = ArrayField(h, "cells", "float32", *w * *hh);
  if (!cells.ok()) return cells.status();
  if (cells->width != *w) return Bad("cells.width", "differs from width");
  s.line = *line;
  s.blocks = *blocks;
  s.cells = *cells;
  return s;
}

uint64_t BytesOf(const ArraySpec& a, int bytes_per_channel) {
  return uint64_t(a.width) * uint64_t(a.height) * 4 * uint64_t(bytes_per_channel);
}

}  // namespace

absl::StatusOr<WaveletTreeReader> WaveletTreeReader::Open(const std::filesystem::path& dir) {
  std::ifstream in(dir / "header.json");
  if (!in)
    return absl::NotFoundError(
        absl::StrCat("header: cannot read ", (dir / "header.json").string()));
  json h = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (h.is_discarded()) return Bad("header", "not valid JSON");
  int w, hh, n, levels, bits, bias;
  absl::StatusOr<Shapes> s = CheckHeader(h, w, hh, n, levels, bits, bias);
  if (!s.ok()) return s.status();
  absl::StatusOr<std::vector<uint8_t>> line =
      ReadAll(dir / s->line.file, BytesOf(s->line, bits / 8), "line");
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
  WaveletTreeReader r;
  absl::StatusOr<Shapes> s =
      CheckHeader(header, r.width_, r.height_, r.n_, r.levels_, r.bits_, r.bias_);
  if (!s.ok()) return s.status();
  if (line.size() != BytesOf(s->line, r.bits_ / 8))
    return Bad("line", "size differs from its shape");
  if (blocks.size() != BytesOf(s->blocks, 4)) return Bad("blocks", "size differs from its shape");
  if (cells.size() != BytesOf(s->cells, 4)) return Bad("cells", "size differs from its shape");
  r.line_texels_ = s->line.texels;
  r.line_.resize(line.size() / (r.bits_ / 8));
  if (r.bits_ == 8) {
    for (size_t i = 0; i < line.size(); ++i) r.line_[i] = line[i];
  } else {
    for (size_t i = 0; i < r.line_.size(); ++i)
      r.line_[i] = uint16_t(line[2 * i] | line[2 * i + 1] << 8);
  }
  r.blocks_.resize(blocks.size() / 4);
  for (size_t i = 0; i < r.blocks_.size(); ++i)
    r.blocks_[i] = uint32_t(blocks[4 * i]) | uint32_t(blocks[4 * i + 1]) << 8 |
                   uint32_t(blocks[4 * i + 2]) << 16 | uint32_t(blocks[4 * i + 3]) << 24;
  r.cells_.resize(cells.size() / 4);
  for (size_t i = 0; i < r.cells_.size(); ++i)
    r.cells_[i] =
        std::bit_cast<float>(uint32_t(cells[4 * i]) | uint32_t(cells[4 * i + 1]) << 8 |
                             uint32_t(cells[4 * i + 2]) << 16 | uint32_t(cells[4 * i + 3]) << 24);
  // Every block's range inside the line, every value finite.
  const int64_t nblocks = int64_t{r.width_} * r.height_ * 6;
  for (int64_t b = 0; b < nblocks; ++b) {
    const uint32_t* e = &r.blocks_[4 * b];
    if (int64_t{e[0]} + e[1] > r.line_texels_)
      return Bad("blocks", absl::StrCat("block ", b, " reaches past the line's texels"));
    if (!std::isfinite(std::bit_cast<float>(e[2])) || !std::isfinite(std::bit_cast<float>(e[3])) ||
        std::bit_cast<float>(e[3]) < 0)
      return Bad("blocks", absl::StrCat("block ", b, " has a non-finite scaling or step"));
  }
  for (int64_t c = 0; c < int64_t{r.width_} * r.height_; ++c) {
    const float a = r.cells_[4 * c + 3];
    if (a != 0 && a != 1) return Bad("cells", absl::StrCat("cell ", c, ": A is not 0 or 1"));
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(r.cells_[4 * c + k]))
        return Bad("cells", absl::StrCat("cell ", c, ": albedo not finite"));
  }
  return r;
}

float WaveletTreeReader::step(int cell, int face) const {
  return std::bit_cast<float>(blocks_[4 * (size_t(cell) * 6 + face) + 3]);
}

absl::Status WaveletTreeReader::DecodeRow(int cell, int face, std::span<float> row) const {
  const int n = n_;
  if (row.size() != size_t(n) * n) return absl::InvalidArgumentError("row: not N² floats");
  std::fill(row.begin(), row.end(), 0.0f);
  const uint32_t* block = &blocks_[4 * (size_t(cell) * 6 + face)];
  const int64_t first = block[0], count = block[1];
  const float step = std::bit_cast<float>(block[3]);
  row[0] = std::bit_cast<float>(block[2]);
  if (count == 0) return absl::OkStatus();
  auto bad = [&](int64_t p, const std::string& why) {
    return absl::InvalidArgumentError(
        absl::StrCat("line: tree of cell ", cell, " face ", face, ", record ", p, ": ", why));
  };
  // One frame per open level ≥ 1: which child of its parent the current
  // square is, the parent's square, and the parent's jump record.
  struct Frame {
    int child = 0, psx = 0, psy = 0;
    int64_t parent_at = 0, jump_offset = 0;
    int jump_code = 0;
  };
  std::vector<Frame> frames(levels_);
  int level = 0, sx = 0, sy = 0;
  const int max_code = (1 << (bits_ - 1)) - 1;
  // Closes level L (≥ 1) when the line moves to `p` with level code `code`.
  auto close = [&](int l, int64_t p, int code) -> absl::Status {
    const Frame& f = frames[l];
    if (f.child != 3) return bad(p, "a group of four siblings is incomplete");
    if (f.parent_at + f.jump_offset != p || f.jump_code != code)
      return bad(p, "a jump does not land past its subtree");
    return absl::OkStatus();
  };
  for (int64_t p = 0;;) {
    if (p >= count) return bad(p, "the line ends inside the tree");
    const uint16_t* t = &line_[4 * (first + p)];
    const int half = 1 << level;
    for (int k = 0; k < 3; ++k) {
      const int q = int(t[k]) - bias_;
      if (q < -max_code || q > max_code) return bad(p, "a code outside the window");
      const int x = k == 1 ? sx : half + sx;
      const int y = k == 0 ? sy : half + sy;
      row[size_t(y) * n + x] = float(q) * step;
    }
    const int a = t[3];
    if (a > levels_) return bad(p, "a level past the finest");
    if (a != 0 && a - 1 > level) {
      if (a - 1 != level + 1) return bad(p, "the next node skips a level");
      if (p + 1 >= count) return bad(p, "a jump record is missing");
      const uint16_t* j = &line_[4 * (first + p + 1)];
      Frame& f = frames[level + 1];
      f = {.child = 0,
           .psx = sx,
           .psy = sy,
           .parent_at = p,
           .jump_offset = int64_t{j[0]} + (int64_t{j[1]} << bits_),
           .jump_code = j[2]};
      ++level;
      sx = 2 * sx;
      sy = 2 * sy;
      p += 2;
      continue;
    }
    ++p;
    const int next = a - 1;  // −1: the tree ends
    for (int l = level; l > std::max(next, 0); --l) {
      if (absl::Status s = close(l, p, a); !s.ok()) return s;
    }
    if (next < 0) {
      if (p != count) return bad(p, "records after the end of the tree");
      return absl::OkStatus();
    }
    if (next == 0) return bad(p, "a second root");
    level = next;
    Frame& f = frames[level];
    if (++f.child > 3) return bad(p, "more than four siblings");
    sx = 2 * f.psx + (f.child & 1);
    sy = 2 * f.psy + (f.child >> 1);
  }
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
