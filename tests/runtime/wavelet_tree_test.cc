// The wavelet-tree export (runtime/gpu/wavelet_tree.h) against its independent
// reader (runtime/gpu/wavelet_tree_reader.h), and both against the store's rows
// truncated by a third, brute-force reading of Boulton §4.4's rule written
// here: perfect reconstruction at cut-off 0, relighting within the
// quantization bound at a real cut-off, hostile headers refused by name.
#include "runtime/gpu/wavelet_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "relight_fixtures.h"
#include "runtime/gpu/wavelet_tree_reader.h"
#include "runtime/relight/sample_rows.h"

namespace wavebake {
namespace {

struct Exported {
  nlohmann::json header;
  std::vector<uint8_t> line, blocks, cells;
};

Exported Export(const WaveletTreeTextures& t) {
  Exported e;
  e.header = WaveletTreeHeader(t, {{"test", true}});
  e.line = t.line;
  e.blocks.resize(t.blocks.size() * 4);
  std::memcpy(e.blocks.data(), t.blocks.data(), e.blocks.size());
  e.cells.resize(t.cells.size() * 4);
  std::memcpy(e.cells.data(), t.cells.data(), e.cells.size());
  return e;
}

absl::StatusOr<WaveletTreeReader> Read(const Exported& e) {
  return WaveletTreeReader::Parse(e.header, e.line, e.blocks, e.cells);
}

class WaveletTreeFixture : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    testing::MiniBakeOptions o;
    o.width = o.height = 16;
    o.light_res = 8;
    bake_ = new testing::MiniBake(testing::RunMiniBake(o));
    auto rows = SampleRows::Decode(bake_->compressed);
    ASSERT_TRUE(rows.ok()) << rows.status();
    rows_ = new SampleRows(*std::move(rows));
  }
  static void TearDownTestSuite() {
    delete rows_;
    delete bake_;
  }
  // Row of (cell, face) as the store decodes it, dense Mallat layout.
  static std::vector<float> StoreRow(int cell, int face) {
    const int per = 64;
    std::vector<float> r(per, 0.0f);
    auto terms = rows_->terms(cell, face);
    auto values = rows_->values(cell, face);
    for (size_t k = 0; k < terms.size(); ++k) r[terms[k] - face * per] = values[k];
    return r;
  }
  static testing::MiniBake* bake_;
  static SampleRows* rows_;
};
testing::MiniBake* WaveletTreeFixture::bake_ = nullptr;
SampleRows* WaveletTreeFixture::rows_ = nullptr;

// §4.4 by brute force over positions: the wavelet at Mallat (x, y) of an
// n-face belongs to square (level, sx, sy); a square is kept when some
// strictly finer square inside its parent's area — or, for the root, any
// square at all — holds a coefficient ≥ cut-off.
std::vector<float> Truncate(const std::vector<float>& row, int n, double cut_off) {
  struct Sq {
    int level, sx, sy;
  };
  auto square_of = [&](int x, int y) {
    const int m = std::max(x, y);
    int level = 0;
    while ((2 << level) <= m) ++level;
    const int half = 1 << level;
    return Sq{level, x >= half ? x - half : x, y >= half ? y - half : y};
  };
  // Is square b inside the area of square a (a coarser or equal)?
  auto inside = [](Sq a, Sq b) {
    const int shift = b.level - a.level;
    return shift >= 0 && (b.sx >> shift) == a.sx && (b.sy >> shift) == a.sy;
  };
  std::vector<Sq> significant;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      if ((x || y) && std::fabs(row[y * n + x]) >= cut_off) significant.push_back(square_of(x, y));
  std::vector<float> out(row.size(), 0.0f);
  out[0] = row[0];
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      if (!x && !y) continue;
      const Sq s = square_of(x, y);
      bool keep = false;
      if (s.level == 0) {
        keep = !significant.empty();
      } else {
        const Sq parent{s.level - 1, s.sx / 2, s.sy / 2};
        for (const Sq& q : significant) keep |= q.level > parent.level && inside(parent, q);
      }
      if (keep) out[y * n + x] = row[y * n + x];
    }
  }
  return out;
}

TEST_F(WaveletTreeFixture, CutOffZeroReconstructsEveryRowWithinHalfAStep) {
  auto t = BuildWaveletTrees(*rows_, bake_->samples, {.cut_off = 0, .bits = 16});
  ASSERT_TRUE(t.ok()) << t.status();
  EXPECT_EQ(t->stats.nodes_kept, t->stats.nodes_total);
  auto r = Read(Export(*t));
  ASSERT_TRUE(r.ok()) << r.status();
  std::vector<float> got(64);
  int sampled = 0;
  for (int cell = 0; cell < 256; ++cell) {
    if (bake_->samples.grid[cell] < 0) continue;
    ++sampled;
    for (int face = 0; face < 6; ++face) {
      ASSERT_TRUE(r->DecodeRow(cell, face, got).ok());
      const std::vector<float> want = StoreRow(cell, face);
      float max_abs = 0;
      for (int j = 1; j < 64; ++j) max_abs = std::max(max_abs, std::fabs(want[j]));
      // 16 bits: the step is the window's max / 32767.
      const float step = r->step(cell, face);
      EXPECT_LE(step, max_abs / 32767 * (1 + 1e-6f));
      EXPECT_EQ(got[0], want[0]);
      for (int j = 1; j < 64; ++j)
        // Half a step, plus the float rounding of c / step and q · step.
        ASSERT_LE(std::fabs(got[j] - want[j]), 0.5f * step + 4 * 0x1p-24f * std::fabs(want[j]))
            << "cell " << cell << " face " << face << " j " << j;
    }
  }
  EXPECT_GT(sampled, 100);
}

TEST_F(WaveletTreeFixture, TruncatedRelightMatchesWithinTheQuantizationBound) {
  // A cut-off that prunes much of each tree: the 75th percentile of |c| ≠ 0.
  std::vector<float> mags;
  for (int cell = 0; cell < 256; ++cell) {
    if (bake_->samples.grid[cell] < 0) continue;
    for (int face = 0; face < 6; ++face)
      for (float v : StoreRow(cell, face))
        if (v != 0) mags.push_back(std::fabs(v));
  }
  std::nth_element(mags.begin(), mags.begin() + mags.size() * 3 / 4, mags.end());
  const double cut_off = mags[mags.size() * 3 / 4];
  for (int bits : {8, 16}) {
    auto t = BuildWaveletTrees(*rows_, bake_->samples, {.cut_off = cut_off, .bits = bits});
    ASSERT_TRUE(t.ok()) << t.status();
    EXPECT_LT(t->stats.nodes_kept, t->stats.nodes_total);
    auto r = Read(Export(*t));
    ASSERT_TRUE(r.ok()) << r.status();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> light(3 * 6 * 64);
    for (float& v : light) v = u(rng);
    auto got = r->Relight(light);
    ASSERT_TRUE(got.ok()) << got.status();
    int beyond = 0;  // cells where the untruncated rows would break the bound
    for (int cell = 0; cell < 256; ++cell) {
      const int32_t id = bake_->samples.grid[cell];
      if (id < 0) {
        EXPECT_TRUE(std::isnan((*got)[3 * cell]));
        continue;
      }
      const float albedo[3] = {bake_->samples.albedo[id].x, bake_->samples.albedo[id].y,
                               bake_->samples.albedo[id].z};
      for (int c = 0; c < 3; ++c) {
        double want = 0, full = 0, bound = 0;
        for (int face = 0; face < 6; ++face) {
          const std::vector<float> row = StoreRow(cell, face);
          const std::vector<float> kept = Truncate(row, 8, cut_off);
          const float step = r->step(cell, face);
          for (int j = 0; j < 64; ++j) {
            const double l = light[3 * (face * 64 + j) + c];
            want += kept[j] * l;
            full += row[j] * l;
            // Each kept wavelet coefficient is within step/2 (rounding), plus
            // float rounding of the products (relative 1e-6 of their size).
            if (j > 0 && kept[j] != 0) bound += 0.5 * step * std::fabs(l);
            bound += 1e-6 * std::fabs(row[j] * l);
          }
        }
        const double err = std::fabs((*got)[3 * cell + c] - want * albedo[c]);
        ASSERT_LE(err, bound * albedo[c] * (1 + 1e-3) + 1e-9) << "cell " << cell << " c " << c;
        beyond += std::fabs((*got)[3 * cell + c] - full * albedo[c]) > bound * albedo[c];
      }
    }
    // The check can fail: compared with the untruncated rows, the same
    // bound breaks in many cells (at 16 bits, where the step is small).
    if (bits == 16) {
      EXPECT_GT(beyond, 100);
    }
  }
}

TEST_F(WaveletTreeFixture, TargetErrorBoundsThePrunedEnergy) {
  for (double target : {0.01, 0.05, 0.2}) {
    auto t = BuildWaveletTrees(*rows_, bake_->samples, {.target_error = target, .bits = 16});
    ASSERT_TRUE(t.ok()) << t.status();
    // Recompute the pruned energy from the reader's rows.
    auto r = Read(Export(*t));
    ASSERT_TRUE(r.ok());
    double total = 0, lost = 0;
    std::vector<float> got(64);
    for (int cell = 0; cell < 256; ++cell) {
      if (bake_->samples.grid[cell] < 0) continue;
      for (int face = 0; face < 6; ++face) {
        ASSERT_TRUE(r->DecodeRow(cell, face, got).ok());
        const std::vector<float> want = StoreRow(cell, face);
        for (int j = 0; j < 64; ++j) {
          total += double{want[j]} * want[j];
          if (got[j] == 0 && want[j] != 0) lost += double{want[j]} * want[j];
        }
      }
    }
    EXPECT_LE(std::sqrt(lost / total), target * 1.001) << target;
    EXPECT_NEAR(t->stats.energy_total, total, 1e-6 * total);
  }
}

class WaveletTreeHostile : public WaveletTreeFixture {
 protected:
  void SetUp() override {
    auto t = BuildWaveletTrees(*rows_, bake_->samples, {.cut_off = 1e-4, .bits = 8});
    ASSERT_TRUE(t.ok());
    good_ = Export(*t);
    ASSERT_TRUE(Read(good_).ok());
  }
  // The reader's error for `e` must exist and name `field`.
  void ExpectRefused(const Exported& e, const std::string& field) {
    auto r = Read(e);
    ASSERT_FALSE(r.ok()) << field;
    EXPECT_NE(std::string(r.status().message()).find(field), std::string::npos)
        << r.status() << " should name " << field;
  }
  Exported good_;
};

TEST_F(WaveletTreeHostile, HeaderFieldsAreRefusedByName) {
  struct Case {
    std::string field;
    std::function<void(nlohmann::json&)> edit;
  };
  const std::vector<Case> cases = {
      {"format", [](auto& h) { h["format"] = "wavebake-wavelet-tree/9"; }},
      {"width", [](auto& h) { h["width"] = -16; }},
      {"height", [](auto& h) { h["height"] = "16"; }},
      {"width", [](auto& h) { h["width"] = 65536, h["height"] = 65536; }},
      {"light_res", [](auto& h) { h["light_res"] = 12; }},
      {"levels", [](auto& h) { h["levels"] = 7; }},
      {"bits", [](auto& h) { h["bits"] = 12; }},
      {"bias", [](auto& h) { h["bias"] = 127; }},
      {"line.file", [](auto& h) { h["line"]["file"] = "../../etc/passwd"; }},
      {"line.type", [](auto& h) { h["line"]["type"] = "float32"; }},
      {"line.height", [](auto& h) { h["line"]["height"] = 1000000; }},
      {"line.texels", [](auto& h) { h["line"]["texels"] = -1; }},
      {"blocks.texels", [](auto& h) { h["blocks"]["texels"] = 5; }},
      {"cells.width", [](auto& h) { h["cells"]["width"] = 8, h["cells"]["height"] = 32; }},
      {"blocks", [](auto& h) { h.erase("blocks"); }},
  };
  for (const Case& c : cases) {
    Exported e = good_;
    c.edit(e.header);
    ExpectRefused(e, c.field);
  }
}

TEST_F(WaveletTreeHostile, ArraysAreRefusedByName) {
  Exported short_line = good_;
  short_line.line.resize(short_line.line.size() - 4);
  ExpectRefused(short_line, "line");
  // A block reaching past the line's texels.
  Exported far = good_;
  const uint32_t huge = 0x7fffffff;
  std::memcpy(&far.blocks[0], &huge, 4);
  ExpectRefused(far, "blocks");
  // A NaN step.
  Exported nan = good_;
  const float q = std::nanf("");
  std::memcpy(&nan.blocks[12], &q, 4);
  ExpectRefused(nan, "blocks");
}

TEST_F(WaveletTreeHostile, CorruptRecordsAreFoundByTheWalk) {
  auto first_tree = [&](const Exported& e) {
    for (size_t b = 0; b < e.blocks.size() / 16; ++b) {
      uint32_t count;
      std::memcpy(&count, &e.blocks[16 * b + 4], 4);
      if (count > 2) return b;
    }
    return size_t{0};
  };
  const size_t b = first_tree(good_);
  uint32_t offset;
  std::memcpy(&offset, &good_.blocks[16 * b], 4);
  const int cell = int(b / 6), face = int(b % 6);
  std::vector<float> row(64);
  {
    auto r = Read(good_);
    ASSERT_TRUE(r.ok());
    ASSERT_TRUE(r->DecodeRow(cell, face, row).ok());
  }
  // Root's level code claims a level past the finest; then a wrong jump.
  Exported level = good_;
  level.line[4 * offset + 3] = 9;
  auto r1 = Read(level);
  ASSERT_TRUE(r1.ok());
  EXPECT_FALSE(r1->DecodeRow(cell, face, row).ok());
  Exported jump = good_;
  jump.line[4 * (offset + 1)] += 1;  // the root's jump offset
  auto r2 = Read(jump);
  ASSERT_TRUE(r2.ok());
  const absl::Status s = r2->DecodeRow(cell, face, row);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(std::string(s.message()).find("line"), std::string::npos) << s;
}

}  // namespace
}  // namespace wavebake
