// Full-depth forward and inverse 2D wavelet transforms of every filter
// (core/wavelets/wavelet2d.h) on 256² and 1024² float images, beside a memcpy of the
// same bytes. Each transform also reports `x_memcpy`: its time per image over
// the copy time of that image measured in the same process just before, so
// the ratio is readable without lining up rows.
//
// Two copy baselines: glibc memcpy, and a copy in 64-byte chunks (inlined
// moves). On the shared build VM glibc's large-copy path is pathologically
// slow for back-to-back 256 KB copies (~90 µs vs ~6 µs for the chunked copy),
// so x_memcpy divides by the faster of the two to stay an honest
// "how many copies of the image does the transform cost". Both sides of the
// ratio are thread CPU time, so other jobs on a shared machine cancel out.
//   ./build/bench_wavelets --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <ctime>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/bake/bake_params_io.h"
#include "core/wavelets/wavelet2d.h"

namespace wavebake {
namespace {

std::vector<float> RandomImage(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> img(static_cast<size_t>(n) * n);
  for (float& v : img) v = u(rng);
  return img;
}

void GlibcCopy(std::span<const float> src, std::span<float> dst) {
  std::memcpy(dst.data(), src.data(), src.size() * sizeof(float));
}

// 16 floats at a time: constant-size memcpy compiles to inline vector moves.
void ChunkedCopy(std::span<const float> src, std::span<float> dst) {
  for (size_t i = 0; i < src.size(); i += 16) std::memcpy(&dst[i], &src[i], 16 * sizeof(float));
}

double ThreadCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

using CopyFn = void (*)(std::span<const float>, std::span<float>);

// Median seconds of back-to-back copies of n² floats (warm caches, like the
// transforms, which also run back to back).
double CopySeconds(CopyFn copy, int n) {
  std::vector<float> src = RandomImage(n), dst(src.size());
  const int reps = 64;
  std::vector<double> t;
  for (int r = 0; r < 9; ++r) {
    const double t0 = ThreadCpuSeconds();
    for (int k = 0; k < reps; ++k) {
      copy(src, dst);
      benchmark::ClobberMemory();
    }
    t.push_back((ThreadCpuSeconds() - t0) / reps);
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

void BM_Copy(benchmark::State& state, CopyFn copy) {
  const int n = static_cast<int>(state.range(0));
  std::vector<float> src = RandomImage(n), dst(src.size());
  for (auto _ : state) {
    copy(src, dst);
    benchmark::DoNotOptimize(dst.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(src.size() * sizeof(float)));
}

void BM_Transform(benchmark::State& state, WaveletFilter f, bool inverse) {
  const int n = static_cast<int>(state.range(0)), depth = MaxDepth(n, n);
  std::vector<float> img = RandomImage(n);
  if (inverse) Forward2d(f, img, n, n, depth);
  const std::vector<float> start = img;
  const double memcpy_s = std::min(CopySeconds(GlibcCopy, n), CopySeconds(ChunkedCopy, n));
  double total_s = 0;
  for (auto _ : state) {
    // Restart from the same data each time so values stay bounded; the copy
    // is outside the timed region.
    state.PauseTiming();
    img = start;
    state.ResumeTiming();
    const double t0 = ThreadCpuSeconds();
    if (inverse) {
      Inverse2d(f, img, n, n, depth);
    } else {
      Forward2d(f, img, n, n, depth);
    }
    benchmark::ClobberMemory();
    total_s += ThreadCpuSeconds() - t0;
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(img.size() * sizeof(float)));
  state.counters["x_memcpy"] = total_s / static_cast<double>(state.iterations()) / memcpy_s;
}

void RegisterAll() {
  benchmark::RegisterBenchmark("memcpy/glibc", BM_Copy, GlibcCopy)->Arg(256)->Arg(1024);
  benchmark::RegisterBenchmark("memcpy/chunked", BM_Copy, ChunkedCopy)->Arg(256)->Arg(1024);
  for (const WaveletFilter f : {WaveletFilter::kHaar, WaveletFilter::kDaub4,
                                WaveletFilter::kLeGall53, WaveletFilter::kCdf97}) {
    for (const bool inverse : {false, true}) {
      const std::string name =
          std::string(inverse ? "inverse/" : "forward/") + std::string(ToString(f));
      benchmark::RegisterBenchmark(name.c_str(), BM_Transform, f, inverse)->Arg(256)->Arg(1024);
    }
  }
}

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  wavebake::RegisterAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
