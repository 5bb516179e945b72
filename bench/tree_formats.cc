// The experiments behind the wavelet-tree format (docs/RESULTS.md, chart 11):
// a store's rows pruned and quantized in ways the exporter does not offer —
// §4.4's sibling groups or significant nodes and their ancestors only, one
// quantization window per tree or per level, the least-squares step —
// relit under one lighting against one reference, traced once and cached.
// Not a benchmark: it prints one line per variant.
//
//   bench_tree_formats STORE ENV TERMS REFERENCE.bin VARIANTS.txt
//
// (bench/tree_formats.txt: the variants of docs/RESULTS.md.)
// REFERENCE.bin: the reference's RGB floats, written on the first run (the
// reference of `wavebake eval`, same options) and read afterwards. Each
// line of VARIANTS.txt: NAME CUT_OFF PRUNE QUANT BITS, with PRUNE `groups`
// (§4.4: the four children of a node kept together) or `live`; QUANT
// `exact` (no rounding), `tree` (one window per tree, the largest kept
// |c| / max code, BITS[0] bits: format 1), `window` (one window per tree
// and level, rounded up to the step minifloat) or `lsq` (the exporter's:
// the least-squares minifloat step at or below the window); BITS the code
// bits per level, level 0 first, comma-separated (one value: every level).
// Bytes are format 2's for the kept nodes and bits (records, jumps over 16
// nodes, step codes, blocks of sampled cells, cells), whatever PRUNE.
// Run from the scene's directory or with WAVEBAKE_SCENE_PATH set.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/products/haar_tree.h"
#include "driver/relight/tree_export.h"
#include "runtime/env/env_map.h"
#include "runtime/gpu/wavelet_tree.h"
#include "runtime/reference/eval.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/sample_rows.h"
#include "runtime/relight/store_relight.h"

using namespace wavebake;

namespace {

struct Variant {
  std::string name, prune, quant;
  double cut_off = 0;
  std::vector<int> bits;
};

struct Lab {
  int n = 0, levels = 0, cells = 0;
  const SampleRows* rows = nullptr;
  const SampleSet* samples = nullptr;
  std::vector<float> light;  // dense 3·6N²
  std::vector<float> reference;
};

// The step minifloat without a bias: the smallest (1 + m/8)·2^e ≥ s.
float MinifloatAtLeast(float s) {
  if (!(s > 0)) return 0;
  int e;
  const double f = 2 * std::frexp(double{s}, &e);  // s = f·2^(e−1), f in [1, 2)
  return static_cast<float>(std::ldexp(1 + std::ceil((f - 1) * 8) / 8, e - 1));
}

float Rounded(float c, float step, int max_code) {
  if (!(step > 0)) return c;
  return std::clamp(std::nearbyint(c / step), -float(max_code), float(max_code)) * step;
}

int ChildId(int l, int sx, int sy, int k) {
  return haar::SquareId(l + 1, 2 * sx + (k & 1), 2 * sy + (k >> 1));
}

void Run(const Lab& lab, const Variant& v) {
  const int n = lab.n, levels = lab.levels, per = n * n, squares = haar::SquaresOf(n);
  std::vector<float> image(3 * size_t(lab.cells), std::nanf(""));
  std::vector<int64_t> kept_at(levels, 0);
  int64_t jumps = 0, trees = 0, sampled = 0;
  double pruned = 0, total = 0;
  std::vector<float> row(per);
  std::vector<std::array<float, 3>> c(squares);
  std::vector<uint8_t> live(squares), keep(squares);
  std::vector<int> below(squares);
  for (int cell = 0; cell < lab.cells; ++cell) {
    const int32_t id = lab.samples->grid[cell];
    if (id < 0) continue;
    ++sampled;
    double b[3] = {0, 0, 0};
    for (int face = 0; face < 6; ++face) {
      std::fill(row.begin(), row.end(), 0.0f);
      const auto terms = lab.rows->terms(cell, face);
      const auto values = lab.rows->values(cell, face);
      for (size_t k = 0; k < terms.size(); ++k) row[terms[k] - face * per] = values[k];
      for (float x : row) total += double{x} * x;
      for (int l = 0; l < levels; ++l)
        for (int sy = 0; sy < (1 << l); ++sy)
          for (int sx = 0; sx < (1 << l); ++sx) {
            const int s = haar::SquareId(l, sx, sy);
            float m = 0;
            for (int t = 0; t < 3; ++t) {
              c[s][t] = row[haar::FaceIndex(n, l, t, sx, sy)];
              m = std::max(m, std::fabs(c[s][t]));
            }
            live[s] = m >= v.cut_off;
          }
      std::fill(below.begin(), below.end(), 0);
      for (int l = levels - 2; l >= 0; --l)
        for (int sy = 0; sy < (1 << l); ++sy)
          for (int sx = 0; sx < (1 << l); ++sx) {
            const int s = haar::SquareId(l, sx, sy);
            for (int k = 0; k < 4; ++k)
              if (live[ChildId(l, sx, sy, k)])
                live[s] = 1, below[s] += 1 + below[ChildId(l, sx, sy, k)];
          }
      std::fill(keep.begin(), keep.end(), 0);
      keep[0] = live[0];
      for (int l = 0; l + 1 < levels; ++l)
        for (int sy = 0; sy < (1 << l); ++sy)
          for (int sx = 0; sx < (1 << l); ++sx) {
            bool any = false;
            for (int k = 0; k < 4; ++k) any |= live[ChildId(l, sx, sy, k)] != 0;
            for (int k = 0; k < 4; ++k) {
              const int ch = ChildId(l, sx, sy, k);
              keep[ch] = v.prune == "groups" ? any && keep[haar::SquareId(l, sx, sy)] : live[ch];
            }
          }
      trees += keep[0] != 0;
      std::vector<float> window(levels, 0.0f);
      float tree_window = 0;
      for (int l = 0; l < levels; ++l)
        for (int s = haar::SquareId(l, 0, 0); s < haar::SquareId(l + 1, 0, 0); ++s) {
          if (!keep[s]) continue;
          ++kept_at[l];
          jumps += l >= 1 && l <= levels - 3 && below[s] >= 16;
          for (float x : c[s]) window[l] = std::max(window[l], std::fabs(x));
          tree_window = std::max(tree_window, window[l]);
        }
      const float* L = &lab.light[3 * size_t(face) * per];
      for (int ch = 0; ch < 3; ++ch) b[ch] += double{row[0]} * L[ch];
      for (int l = 0; l < levels; ++l) {
        const int max_code = (1 << (v.bits[l] - 1)) - 1;
        const int first = haar::SquareId(l, 0, 0), last = haar::SquareId(l + 1, 0, 0);
        float step = 0;
        if (v.quant == "tree") step = tree_window / float((1 << (v.bits[0] - 1)) - 1);
        if (v.quant == "window" || v.quant == "lsq") step = MinifloatAtLeast(window[l] / max_code);
        if (v.quant == "lsq" && step > 0) {
          double best = -1;
          float best_step = step;
          for (int k = 0; k <= 24; ++k) {  // the grid points at and below: 8 an octave
            const float s = MinifloatAtLeast(float(step * std::exp2(-k / 8.0) * (1 - 1e-6)));
            double e = 0;
            for (int q = first; q < last; ++q)
              if (keep[q])
                for (float x : c[q]) e += std::pow(double{Rounded(x, s, max_code)} - x, 2);
            if (best < 0 || e < best) best = e, best_step = s;
          }
          step = best_step;
        }
        for (int q = first; q < last; ++q) {
          for (int t = 0; t < 3; ++t) {
            if (!keep[q]) {
              pruned += double{c[q][t]} * c[q][t];
              continue;
            }
            const double x = v.quant == "exact" ? c[q][t] : Rounded(c[q][t], step, max_code);
            const int sx = (q - first) % (1 << l), sy = (q - first) >> l;
            const int j = haar::FaceIndex(n, l, t, sx, sy);
            for (int ch = 0; ch < 3; ++ch) b[ch] += x * L[3 * j + ch];
          }
        }
      }
    }
    const Vec3 a = lab.samples->albedo[id];
    image[3 * cell] = float(b[0] * a.x);
    image[3 * cell + 1] = float(b[1] * a.y);
    image[3 * cell + 2] = float(b[2] * a.z);
  }
  double units = 4.0 * jumps + 2.0 * levels * trees;
  int64_t kept = 0;
  for (int l = 0; l < levels; ++l) {
    units += double(RecordNibbles(l, levels, v.bits[l])) * kept_at[l];
    kept += kept_at[l];
  }
  const double bytes = units / 2 + 48.0 * sampled + 16.0 * lab.cells;
  auto e = CompareFinite(image, lab.reference, "the variant's relighting");
  std::printf(
      "%-22s cut-off %-8.3g %-6s %-6s kept %8lld (%5.2f%%)  ~%6.3f MB  pruned %.4f  "
      "rel_rms %.4f%%\n",
      v.name.c_str(), v.cut_off, v.prune.c_str(), v.quant.c_str(), (long long)kept,
      100.0 * kept / (double(squares) * 6 * sampled), bytes / 1e6, std::sqrt(pruned / total),
      e.ok() ? 100 * e->rel_rms : -1.0);
  std::fflush(stdout);
}

int Fail(const absl::Status& s) {
  std::fprintf(stderr, "%s\n", s.ToString().c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: %s STORE ENV TERMS REFERENCE.bin VARIANTS.txt\n", argv[0]);
    return 2;
  }
  const std::string store = argv[1], env_spec = argv[2], cache = argv[4], spec = argv[5];
  const int terms = std::atoi(argv[3]);
  auto env = LoadEnvMap(env_spec);
  if (!env.ok()) return Fail(env.status());
  auto source = driver::OpenTreeSource(store);
  if (!source.ok()) return Fail(source.status());
  auto rows = SampleRows::Decode(source->columns);
  if (!rows.ok()) return Fail(rows.status());
  Lab lab;
  lab.rows = &*rows;
  lab.samples = &source->samples;
  lab.n = rows->light_res();
  lab.levels = haar::LevelsOf(lab.n);
  lab.cells = rows->cells();
  auto lighting = LightingFromEnv(*env, lab.n, WaveletFilter::kHaar);
  if (!lighting.ok()) return Fail(lighting.status());
  auto lights = SelectWaveletLights(*lighting, terms);
  if (!lights.ok()) return Fail(lights.status());
  lab.light.assign(3 * 6 * size_t(lab.n) * lab.n, 0.0f);
  for (const WaveletLight& l : lights->lights)
    for (int c = 0; c < 3; ++c) lab.light[3 * size_t(l.column) + c] = l.weight[c];
  lab.reference.resize(3 * size_t(lab.cells));
  std::ifstream in(cache, std::ios::binary);
  if (!in || !in.read(reinterpret_cast<char*>(lab.reference.data()), lab.reference.size() * 4)) {
    auto opened = OpenStore(store);
    if (!opened.ok()) return Fail(opened.status());
    auto caster = BuildBakedScene(opened->info);
    if (!caster.ok()) return Fail(caster.status());
    ReferenceOptions options;
    options.epsilon = BakedEpsilon(opened->info, *caster);
    auto ref = ComputeReference(*caster, opened->samples, *env, options);
    if (!ref.ok()) return Fail(ref.status());
    lab.reference = ref->rgb;
    std::ofstream out(cache, std::ios::binary);
    out.write(reinterpret_cast<const char*>(lab.reference.data()), lab.reference.size() * 4);
    auto image = RelightImage(*opened, *env, terms);
    if (!image.ok()) return Fail(image.status());
    auto e = CompareFinite(*image, lab.reference, "the store's relighting");
    if (!e.ok()) return Fail(e.status());
    std::printf("reference traced (rel_se %.5f); the store: rel_rms %.4f%%\n", ref->rel_se,
                100 * e->rel_rms);
  }
  std::ifstream variants(spec);
  if (!variants) return Fail(absl::NotFoundError("cannot read " + spec));
  std::string line;
  while (std::getline(variants, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    Variant v;
    std::string bits;
    if (!(words >> v.name >> v.cut_off >> v.prune >> v.quant >> bits) ||
        (v.prune != "groups" && v.prune != "live") ||
        (v.quant != "exact" && v.quant != "tree" && v.quant != "window" && v.quant != "lsq"))
      return Fail(absl::InvalidArgumentError("variants: cannot read '" + line + "'"));
    auto parsed = ParseCodeBits(bits);
    if (!parsed.ok() || parsed->empty()) return Fail(absl::InvalidArgumentError("bits: " + bits));
    v.bits = *parsed;
    if (v.bits.size() == 1) v.bits.assign(lab.levels, v.bits[0]);
    if (static_cast<int>(v.bits.size()) != lab.levels)
      return Fail(absl::InvalidArgumentError("bits: not one per level: " + bits));
    Run(lab, v);
  }
  return 0;
}
