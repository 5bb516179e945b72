#include "tests/worker/column_test_support.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "worker/columns/transform_columns.h"

namespace wavebake::column_testing {

std::unique_ptr<BakeContext> MakeContext(const BakeParams& params, const std::string& layout) {
  BakeParams p = params;
  p.layout = layout;
  absl::StatusOr<std::unique_ptr<BakeContext>> ctx = MakeBakeContext("builtin:furnace", p);
  if (!ctx.ok()) throw std::runtime_error(std::string(ctx.status().message()));
  return *std::move(ctx);
}

void WriteSyntheticStaging(const JobPlan& plan, const std::filesystem::path& store,
                           const ColumnImage& image) {
  ASSERT_TRUE(WriteGroup(store).ok());
  ASSERT_TRUE(WriteGroup(store::Path(store, store::kStaging)).ok());
  absl::StatusOr<ZarrArray> transport =
      ZarrArray::Create(store::Path(store, store::kStagingTransport),
                        {.shape = {plan.columns, int64_t{plan.width} * plan.height},
                         .chunks = {plan.group_size, plan.tile_cells()}});
  absl::StatusOr<ZarrArray> energy = ZarrArray::Create(
      store::Path(store, store::kStagingTileEnergy), {.shape = {plan.tiles()}, .chunks = {1}});
  ASSERT_TRUE(transport.ok()) << transport.status();
  ASSERT_TRUE(energy.ok()) << energy.status();
  std::vector<float> chunk(size_t(plan.group_size) * plan.tile_cells());
  for (int t = 0; t < plan.tiles(); ++t) {
    const TileRect r = plan.Tile(t);
    double sum = 0;
    for (int g = 0; g < plan.groups; ++g) {
      std::fill(chunk.begin(), chunk.end(), 0.0f);
      for (int c = 0; c < plan.GroupCount(g); ++c) {
        for (int i = 0; i < plan.tile_cells(); ++i) {
          const float v = image(plan.GroupFirst(g) + c, r.x0 + i % r.width, r.y0 + i / r.width);
          chunk[size_t(c) * plan.tile_cells() + i] = v;
          sum += double(v) * v;
        }
      }
      const int64_t index[2] = {g, t};
      ASSERT_TRUE(transport->WriteChunk<float>(index, chunk).ok());
    }
    const int64_t index[1] = {t};
    const float e = float(sum);
    ASSERT_TRUE(energy->WriteChunk<float>(index, std::span(&e, 1)).ok());
  }
}

void TransformAll(const BakeContext& ctx, const std::filesystem::path& store,
                  std::vector<int> order) {
  if (order.empty()) {
    for (int g = 0; g < ctx.plan.groups; ++g) order.push_back(g);
  }
  for (int g : order) {
    const absl::Status s = TransformColumns(ctx, store, g, nullptr);
    ASSERT_TRUE(s.ok()) << s;
  }
}

ProcessResult RunPython(const std::filesystem::path& work_dir, const std::string& script) {
  {
    std::ofstream out(work_dir / "check.py");
    out << script;
  }
  const std::string command = "cd '" + work_dir.string() + "' && /usr/bin/python3 check.py 2>&1";
  ProcessResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buf[4096];
  while (size_t n = std::fread(buf, 1, sizeof buf, pipe)) result.output.append(buf, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace wavebake::column_testing
