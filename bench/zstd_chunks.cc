// zstd level 1 on one 1 MiB float32 chunk (DESIGN.md §3: one frame per chunk,
// content size + checksum), for smooth data (a staging chunk of transport
// values) and sparse data (mostly zeros, like quantized column output), each
// beside a memcpy of the same bytes in the same run.
//   ./build/bench_zstd_chunks --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "storage/zarr/zstd_codec.h"

namespace wavebake {
namespace {

constexpr size_t kFloats = (1 << 20) / sizeof(float);  // 1 MiB
constexpr int kSide = 512;                             // 512 × 512 image

enum Data { kSmooth, kSparse };

std::vector<float> MakeChunk(Data data) {
  std::vector<float> v(kFloats, 0.0f);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      float& f = v[y * kSide + x];
      if (data == kSmooth) {
        f = 0.5f + 0.3f * std::sin(0.02f * x) * std::cos(0.013f * y);
      } else if (u(rng) < 0.05f) {
        f = u(rng) - 0.5f;  // ~5 % nonzero
      }
    }
  }
  return v;
}

std::span<const std::byte> Bytes(const std::vector<float>& v) {
  return std::as_bytes(std::span(v));
}

void BM_Memcpy(benchmark::State& state, Data data) {
  const std::vector<float> src = MakeChunk(data);
  std::vector<float> dst(src.size());
  for (auto _ : state) {
    std::memcpy(dst.data(), src.data(), src.size() * sizeof(float));
    benchmark::DoNotOptimize(dst.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * int64_t(src.size() * sizeof(float)));
}

void BM_Compress(benchmark::State& state, Data data) {
  const std::vector<float> src = MakeChunk(data);
  size_t frame_bytes = 0;
  for (auto _ : state) {
    absl::StatusOr<std::vector<std::byte>> frame = ZstdCompress(Bytes(src), 1);
    if (!frame.ok()) state.SkipWithError(std::string(frame.status().message()).c_str());
    frame_bytes = frame->size();
    benchmark::DoNotOptimize(frame->data());
  }
  state.SetBytesProcessed(state.iterations() * int64_t(src.size() * sizeof(float)));
  state.counters["ratio"] = double(src.size() * sizeof(float)) / double(frame_bytes);
}

void BM_Decompress(benchmark::State& state, Data data) {
  const std::vector<float> src = MakeChunk(data);
  const std::vector<std::byte> frame = *ZstdCompress(Bytes(src), 1);
  std::vector<std::byte> out(src.size() * sizeof(float));
  for (auto _ : state) {
    absl::Status s = ZstdDecompressInto(frame, out, "bench");
    if (!s.ok()) state.SkipWithError(std::string(s.message()).c_str());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetBytesProcessed(state.iterations() * int64_t(out.size()));
  state.counters["ratio"] = double(out.size()) / double(frame.size());
}

BENCHMARK_CAPTURE(BM_Memcpy, smooth, kSmooth)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compress, smooth, kSmooth)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Decompress, smooth, kSmooth)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Memcpy, sparse, kSparse)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Compress, sparse, kSparse)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Decompress, sparse, kSparse)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace wavebake

BENCHMARK_MAIN();
