// Glossy frame rate (runtime/glossy/glossy_relighter.h: the Haar triple product of
// a visibility store) on one core, beside the brute-force per-sample product
// of dense decoded rows measured in the same run.
//
// The store: builtin:sphere-plane, camera:128x128, N = 32 (M = 6144), K = 4,
// --transport visibility, target 1 %, baked at start-up (or WB_GLOSSY_STORE,
// a store of that kind). Material phong:32 (256 BRDF terms per sample), the
// baked camera's view, grace.hdr at 256 lighting terms. A frame is one
// Relight (thread CPU time; the slices are projected once, outside).
//
// The baselines compute the same B(x) = Σ L V ρ per sample from dense rows
// decoded beforehand (outside the timing), on every 8th sample (16th for
// the slowest; the frame time is the per-sample time × the samples; dense
// rows of all 16384 would take 0.8 GB), the same 256-term L:
//   tripling     Eq. 17 by brute force: Σ C(i,j,k) L_i V_j ρ_k over every
//                nonzero tripling coefficient of a face (Theorem 7's three
//                cases listed once, 40 k triples per face at N = 32), the
//                decoded V row and the whole BRDF slice dense;
//   dense_rows   every coefficient of the row basis through the tree
//                algorithm instead (HaarProduct::Accumulate into a dense W,
//                then Σ_m V_m W_m);
//   dense_pixels the pixel basis: V, ρ and L texel by texel, Σ_m L_m V_m ρ_m
//                (ρ tabulated per texel beforehand): the cheapest dense form.
// `x_<baseline>` is that frame time over the glossy frame time.
//   ./build/bench_glossy --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <time.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <tuple>
#include <vector>

#include "core/products/haar_product.h"
#include "core/products/haar_tree.h"
#include "driver/bake/embedded_bake.h"
#include "runtime/glossy/glossy_store.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/row_basis.h"
#include "storage/files/scoped_dir.h"

namespace wavebake {
namespace {

constexpr int kTerms = 256;
constexpr int kEvery = 8;  // baselines: every 8th sample

double ThreadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

template <typename T>
T Must(absl::StatusOr<T> v) {
  if (!v.ok()) {
    std::fprintf(stderr, "bench_glossy: %s\n", std::string(v.status().message()).c_str());
    std::exit(1);
  }
  return *std::move(v);
}

struct Fixture {
  std::unique_ptr<ScopedDir> dir;
  std::unique_ptr<GlossyStore> store;
  WaveletLights lights;
  std::vector<float> image;
  std::vector<int> cells;  // the baselines' samples
  double tripling_seconds = 0, dense_rows_seconds = 0, dense_pixels_seconds = 0;  // per frame
};

// Every nonzero tripling coefficient of one n×n face (Theorem 7; the
// ordered triples, C as core/products/tripling.h has it).
struct Triple {
  uint16_t i, j, k;
  float c;
};
std::vector<Triple> FaceTriples(int n) {
  std::vector<Triple> out;
  auto add3 = [&](int a, int b, float coeff) {  // the 3 orders of (a, a, b)
    out.push_back({uint16_t(a), uint16_t(a), uint16_t(b), coeff});
    out.push_back({uint16_t(a), uint16_t(b), uint16_t(a), coeff});
    out.push_back({uint16_t(b), uint16_t(a), uint16_t(a), coeff});
  };
  out.push_back({0, 0, 0, 1.0f / n});
  for (int p = 1; p < n * n; ++p) {
    const haar::Position pos = haar::Decode(p % n, p / n);
    if (pos.type == 0) {  // case 2, once per square: the 6 orders of its 3 types
      const int t[3] = {p, haar::FaceIndex(n, pos.level, 1, pos.sx, pos.sy),
                        haar::FaceIndex(n, pos.level, 2, pos.sx, pos.sy)};
      const float c = static_cast<float>(1 << pos.level) / n;
      for (auto [a, b, d] :
           {std::tuple{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}})
        out.push_back({uint16_t(t[a]), uint16_t(t[b]), uint16_t(t[d]), c});
    }
    add3(p, 0, 1.0f / n);  // case 3: the scaling function, then every coarser wavelet
    for (int l = pos.level - 1, sx = pos.sx, sy = pos.sy; l >= 0; --l) {
      const int q = haar::QuadrantInParent(sx, sy);
      sx >>= 1, sy >>= 1;
      for (int t = 0; t < 3; ++t)
        add3(p, haar::FaceIndex(n, l, t, sx, sy),
             haar::QuadrantSign(t, q) * static_cast<float>(1 << l) / n);
    }
  }
  return out;
}

std::filesystem::path StorePath(Fixture& f) {
  if (const char* s = std::getenv("WB_GLOSSY_STORE")) return s;
  f.dir = std::make_unique<ScopedDir>(std::filesystem::temp_directory_path() /
                                      ("wavebake-bench-glossy-" + std::to_string(getpid())));
  const std::filesystem::path out = f.dir->path() / "sp128.wbk";
  std::filesystem::create_directories(f.dir->path());
  BakeParams p;
  p.layout = "camera:128x128";
  p.light_res = 32;
  p.transport = Transport::kVisibility;
  std::fprintf(stderr, "baking builtin:sphere-plane camera:128x128 N=32 visibility ...\n");
  const v1::Job job = Must(driver::EmbeddedBake("builtin:sphere-plane", p, out, {}));
  if (job.phase() != v1::PHASE_DONE) {
    std::fprintf(stderr, "bench_glossy: bake failed: %s\n", job.error().c_str());
    std::exit(1);
  }
  return out;
}

// Best of 3 of `frame` (thread CPU seconds), scaled from the sampled cells
// to the whole grid.
template <typename Frame>
double BestPerFrame(const Fixture& f, const Frame& frame) {
  double best = 1e30;
  for (int r = 0; r < 3; ++r) {
    const double t0 = ThreadSeconds();
    frame();
    best = std::min(best, ThreadSeconds() - t0);
  }
  int unmasked = 0;
  for (int32_t id : f.store->samples().grid) unmasked += id >= 0;
  return best * unmasked / static_cast<double>(f.cells.size());
}

void MeasureBaselines(Fixture& f) {
  GlossyStore& g = *f.store;
  const int n = g.info().light_res, m_count = 6 * n * n;
  const HaarFactor lighting = LightingFactor(f.lights);
  // L's 256 terms in the pixel basis.
  std::vector<float> l_pix(lighting.rgb().begin(), lighting.rgb().end());
  InverseRowTransformCube(WaveletFilter::kHaar, n, l_pix);
  const BrdfSlices full = Must(g.Project(g.brdf(), {.terms = 0}));
  const BrdfTexels texels(&g.pattern());
  // Dense rows and slices, decoded and tabulated outside the timing.
  std::vector<std::vector<float>> v_rows, v_pix, rho_pix;
  for (int cell : f.cells) {
    std::vector<float> row(m_count, 0.0f);
    for (int face = 0; face < 6; ++face) {
      const auto t = g.rows().terms(cell, face);
      const auto v = g.rows().values(cell, face);
      for (size_t k = 0; k < t.size(); ++k) row[t[k]] = v[k];
    }
    std::vector<float> pix = row;
    std::vector<float> rgb(3 * m_count);  // InverseRowTransformCube wants RGB
    for (int m = 0; m < m_count; ++m) rgb[3 * m] = rgb[3 * m + 1] = rgb[3 * m + 2] = row[m];
    InverseRowTransformCube(WaveletFilter::kHaar, n, rgb);
    for (int m = 0; m < m_count; ++m) pix[m] = rgb[3 * m];
    std::vector<float> rho(m_count, 0.0f);
    const int32_t s = g.samples().grid[cell];
    texels.Evaluate(g.brdf(), g.samples().normal[s], g.views()[cell], 0, rho);
    v_rows.push_back(std::move(row));
    v_pix.push_back(std::move(pix));
    rho_pix.push_back(std::move(rho));
  }
  // Dense slices too, for the enumeration.
  std::vector<std::vector<float>> rho_rows;
  for (int cell : f.cells) {
    std::vector<float> rho(m_count, 0.0f);
    const auto idx = full.Index(cell);
    const auto val = full.Value(cell);
    for (size_t k = 0; k < idx.size(); ++k) rho[idx[k]] = val[k];
    rho_rows.push_back(std::move(rho));
  }
  const std::vector<Triple> triples = FaceTriples(n);
  const int per_face = n * n;
  std::vector<float> out_tri(3 * f.cells.size());
  std::vector<int> every_other;  // the enumeration is slow: half the sampled cells
  for (size_t i = 0; i < f.cells.size(); i += 2) every_other.push_back(static_cast<int>(i));
  const double tri = BestPerFrame(f, [&] {
    for (int i : every_other) {
      float b[3] = {0, 0, 0};
      for (int face = 0; face < 6; ++face) {
        const float* l = lighting.rgb().data() + 3 * face * per_face;
        const float* v = v_rows[i].data() + face * per_face;
        const float* r = rho_rows[i].data() + face * per_face;
        for (const Triple& t : triples) {
          const float vr = t.c * v[t.j] * r[t.k];
          for (int c = 0; c < 3; ++c) b[c] += vr * l[3 * t.i + c];
        }
      }
      for (int c = 0; c < 3; ++c) out_tri[3 * i + c] = b[c];
    }
    benchmark::DoNotOptimize(out_tri.data());
  });
  f.tripling_seconds = tri * f.cells.size() / every_other.size();
  std::fprintf(stderr, "tripling: %zu nonzero coefficients per face\n", triples.size());

  std::vector<float> out(3 * f.cells.size());
  HaarProduct product(n);
  RgbCube w(n);
  f.dense_rows_seconds = BestPerFrame(f, [&] {
    for (size_t i = 0; i < f.cells.size(); ++i) {
      product.Accumulate(lighting, full.Index(f.cells[i]), full.Value(f.cells[i]), w);
      float b[3] = {0, 0, 0};
      const float* v = v_rows[i].data();
      for (int m = 0; m < m_count; ++m)
        for (int c = 0; c < 3; ++c) b[c] += v[m] * w.rgb[3 * m + c];
      w.touched.fill(true);
      w.Clear();
      for (int c = 0; c < 3; ++c) out[3 * i + c] = b[c];
    }
    benchmark::DoNotOptimize(out.data());
  });
  std::vector<float> out_pix(3 * f.cells.size());
  f.dense_pixels_seconds = BestPerFrame(f, [&] {
    for (size_t i = 0; i < f.cells.size(); ++i) {
      float b[3] = {0, 0, 0};
      const float *v = v_pix[i].data(), *rho = rho_pix[i].data();
      for (int m = 0; m < m_count; ++m) {
        const float vr = v[m] * rho[m];
        for (int c = 0; c < 3; ++c) b[c] += vr * l_pix[3 * m + c];
      }
      for (int c = 0; c < 3; ++c) out_pix[3 * i + c] = b[c];
    }
    benchmark::DoNotOptimize(out_pix.data());
  });
  // The three answers agree: the baselines exactly, the glossy frame up to
  // its 256-term BRDF slices.
  g.relighter().Transport(lighting, g.relighter().slices(), f.image);
  double d_base = 0, d_fast = 0, d_tri = 0, norm = 0, norm_tri = 0;
  for (size_t i = 0; i < f.cells.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      if (i % 2 == 0) {
        d_tri += std::pow(out_tri[3 * i + c] - out_pix[3 * i + c], 2);
        norm_tri += std::pow(out_pix[3 * i + c], 2);
      }
      d_base += std::pow(out[3 * i + c] - out_pix[3 * i + c], 2);
      d_fast += std::pow(f.image[3 * f.cells[i] + c] - out_pix[3 * i + c], 2);
      norm += std::pow(out_pix[3 * i + c], 2);
    }
  }
  std::fprintf(stderr,
               "vs dense_pixels: tripling rel %.2e, dense_rows rel %.2e, glossy (256 BRDF terms) "
               "rel %.4f\n",
               std::sqrt(d_tri / norm_tri), std::sqrt(d_base / norm), std::sqrt(d_fast / norm));
}

Fixture& GetFixture() {
  static Fixture f = [] {
    Fixture fx;
    const std::filesystem::path path = StorePath(fx);
    fx.store =
        Must(GlossyStore::Open(path, {.brdf = "phong:32", .eye = {}, .slices = {}, .threads = 1}));
    // What the relighter holds besides the store: V decoded once, and the
    // per-sample BRDF slices (the table Ng 2004 would tabulate over normals).
    const SampleRows::Stats& rows = fx.store->rows().stats();
    const BrdfSlices& slices = fx.store->relighter().slices();
    std::fprintf(stderr,
                 "visibility rows: %lld entries, %.1f MiB, decoded in %.2f s; phong:32 slices: "
                 "%zu coefficients, %.1f MiB, projected in %.2f s (one core)\n",
                 static_cast<long long>(rows.nonzeros), rows.bytes / 1048576.0, rows.seconds,
                 slices.value.size(), slices.bytes() / 1048576.0, slices.seconds);
    const EnvMap env = Must(LoadEnvMap(WB_SHARED_DATA "/probes/grace.hdr"));
    const LightingCoefficients l =
        Must(LightingFromEnv(env, fx.store->info().light_res, WaveletFilter::kHaar));
    fx.lights = Must(SelectWaveletLights(l, kTerms));
    fx.image.resize(3 * fx.store->samples().cells());
    int unmasked = 0;
    for (int c = 0; c < fx.store->samples().cells(); ++c) {
      if (fx.store->samples().grid[c] < 0) continue;
      if (unmasked++ % kEvery == 0) fx.cells.push_back(c);
    }
    MeasureBaselines(fx);
    return fx;
  }();
  return f;
}

void BM_GlossyFrame(benchmark::State& state) {
  Fixture& f = GetFixture();
  GlossyRelighter& r = f.store->relighter();
  r.Relight(f.lights, f.image);  // warm
  double total = 0;
  for (auto _ : state) {
    const double t0 = ThreadSeconds();
    r.Relight(f.lights, f.image);
    benchmark::DoNotOptimize(f.image.data());
    benchmark::ClobberMemory();
    total += ThreadSeconds() - t0;
  }
  const double per_frame = total / static_cast<double>(state.iterations());
  state.counters["fps"] = 1 / per_frame;
  state.counters["x_tripling"] = f.tripling_seconds / per_frame;
  state.counters["x_dense_rows"] = f.dense_rows_seconds / per_frame;
  state.counters["x_dense_pixels"] = f.dense_pixels_seconds / per_frame;
  state.counters["tripling_ms"] = 1e3 * f.tripling_seconds;
  state.counters["dense_rows_ms"] = 1e3 * f.dense_rows_seconds;
  state.counters["dense_pixels_ms"] = 1e3 * f.dense_pixels_seconds;
}

BENCHMARK(BM_GlossyFrame)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
