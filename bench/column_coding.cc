// CodeColumn (core/columns/column_coding.h) alone, on every column of a real job's
// staged T held in memory: the per-column math of TRANSFORM_COLUMNS without
// its I/O. --case=bunny (hilbert 64×64, N=32, default) or cubes-wall (camera
// 64×64, N=32), traced by brute force, K=4.
//
//   build/bench_column_coding [--case=bunny] --benchmark_repetitions=3
//
// Counters: ns per column cell (ns/cell), the kept coefficients, and the
// share of columns whose energy fits in the budget (they keep nothing).
// Adaptive runs twice: by_size:1 as the bake codes (each group's columns
// coded both ways, core/columns/group_codings.h), by_size:0 by count alone.
#include "core/columns/column_coding.h"

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/columns/group_codings.h"
#include "storage/store/store_layout.h"
#include "storage/store/transport_bytes.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/transform_columns.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/bake_tile.h"
#include "worker/tiles/recode.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

[[noreturn]] void Die(const std::string& what) {
  std::fprintf(stderr, "bench_column_coding: %s\n", what.c_str());
  std::exit(1);
}

void Check(const absl::Status& s) {
  if (!s.ok()) Die(s.ToString());
}

struct Case {
  std::string name, scene, layout;
  int light_res;
};

const Case kCases[] = {
    {"bunny", std::string(WB_SHARED_DATA) + "/models/bunny.obj", "hilbert:64x64", 32},
    {"cubes-wall", "builtin:cubes-wall", "camera:64x64", 32},
};
Case g_case = kCases[0];

// The staged T of the case as column images, column m at [m·W·H, (m+1)·W·H).
struct Columns {
  std::unique_ptr<BakeContext> ctx;
  std::vector<float> images;
  double matrix_energy = 0;

  Columns() {
    BakeParams p;
    p.light_res = g_case.light_res;
    p.layout = g_case.layout;
    p.refine = false;
    absl::StatusOr<std::unique_ptr<BakeContext>> made = MakeBakeContext(g_case.scene, p);
    if (!made.ok()) Die(made.status().ToString());
    ctx = *std::move(made);
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("wavebake-bench-coding-" + std::to_string(::getpid()));
    if (!TraceStaging(*ctx, dir, {.threads = 2}).ok()) Die("trace failed");
    const JobPlan& plan = ctx->plan;
    absl::StatusOr<double> energy = ReadMatrixEnergy(plan, dir);
    if (!energy.ok()) Die(energy.status().ToString());
    matrix_energy = *energy;
    absl::StatusOr<ZarrArray> staging = ZarrArray::Open(store::Path(dir, store::kStagingTransport));
    if (!staging.ok()) Die(staging.status().ToString());
    const size_t cells = size_t(plan.width) * plan.height;
    images.assign(size_t(plan.columns) * cells, 0.0f);
    std::vector<float> chunk(size_t(plan.group_size) * plan.tile_cells());
    for (int g = 0; g < plan.groups; ++g) {
      for (int t = 0; t < plan.tiles(); ++t) {
        const int64_t index[2] = {g, t};
        Check(staging->ReadChunkInto(index, std::as_writable_bytes(std::span(chunk))));
        const TileRect r = plan.Tile(t);
        for (int c = 0; c < plan.GroupCount(g); ++c) {
          float* dst = images.data() + size_t(plan.GroupFirst(g) + c) * cells;
          for (int y = 0; y < r.height; ++y)
            std::copy_n(chunk.data() + size_t(c) * plan.tile_cells() + y * r.width, r.width,
                        dst + size_t(r.y0 + y) * plan.width + r.x0);
        }
      }
    }
    std::filesystem::remove_all(dir);
  }
};

Columns& GetColumns() {
  static Columns columns;
  return columns;
}

void BM_CodeColumn(benchmark::State& state) {
  Columns& c = GetColumns();
  BakeParams params = c.ctx->params;
  params.column_mode = static_cast<ColumnMode>(state.range(0));
  const JobPlan& plan = c.ctx->plan;
  const ColumnCodingParams p =
      MakeColumnCodingParams(params, plan.width, plan.height, c.matrix_energy);
  // by_size 1: as TRANSFORM_COLUMNS codes (both codings of each column, the
  // choice per group); 0: the fewest coefficients alone, the baseline.
  const bool by_size = state.range(1) != 0;
  const size_t cells = size_t(plan.width) * plan.height;
  std::vector<ColumnCodings> codings(plan.group_size);
  uint64_t kept = 0;
  int empty = 0;
  for (auto _ : state) {
    kept = 0;
    empty = 0;
    for (int g = 0; g < plan.groups; ++g) {
      codings.resize(plan.GroupCount(g));
      for (int j = 0; j < plan.GroupCount(g); ++j) {
        const int m = plan.GroupFirst(g) + j;
        CodeColumn(p, std::span(c.images).subspan(m * cells, cells), &codings[j].fewest, 0,
                   by_size ? &codings[j].flat : nullptr);
        empty += codings[j].fewest.energy <=
                 p.target_error * p.target_error * codings[j].fewest.reference_energy;
      }
      // Without depth-0 codings (by_size:0) the choice is fewest everywhere.
      const std::vector<uint8_t> use_flat =
          ChooseGroupCodings(p, codings, plan.GroupFirst(g), TransportBytes);
      for (size_t j = 0; j < codings.size(); ++j)
        kept += (use_flat[j] ? codings[j].flat : codings[j].fewest).positions.size();
    }
  }
  state.counters["ns/cell"] = benchmark::Counter(
      double(plan.columns) * cells * state.iterations(),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
  state.counters["kept"] = double(kept);
  state.counters["fits_budget"] = double(empty) / plan.columns;
  state.SetLabel(g_case.name);
}
BENCHMARK(BM_CodeColumn)
    ->ArgNames({"mode", "by_size"})
    ->Args({int(ColumnMode::k2d), 0})
    ->Args({int(ColumnMode::kFull), 0})
    ->Args({int(ColumnMode::kAdaptive), 0})
    ->Args({int(ColumnMode::kAdaptive), 1})
    ->ComputeStatistics("min",
                        [](const std::vector<double>& v) {
                          return *std::min_element(v.begin(), v.end());
                        })
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wavebake

int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--case=", 0) != 0) {
      rest.push_back(argv[i]);
      continue;
    }
    bool found = false;
    for (const wavebake::Case& c : wavebake::kCases)
      if (arg.substr(7) == c.name) wavebake::g_case = c, found = true;
    if (!found) wavebake::Die("--case: bunny or cubes-wall");
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
