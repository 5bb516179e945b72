#include "driver/relight/staged_relight.h"

#include <limits>

#include "absl/strings/str_cat.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "worker/tiles/row_transform.h"

namespace wavebake::driver {

absl::StatusOr<std::vector<float>> RelightStaging(const BakeContext& ctx,
                                                  const std::filesystem::path& traced,
                                                  std::span<const float> cube_rgb) {
  const JobPlan& plan = ctx.plan;
  const size_t m_count = plan.columns;
  if (cube_rgb.size() != 3 * m_count)
    return absl::InvalidArgumentError(
        absl::StrCat("lighting: ", cube_rgb.size(), " floats for ", m_count, " texels"));
  // L per channel in the row-transform basis.
  std::vector<float> light[3];
  for (int c = 0; c < 3; ++c) {
    light[c].resize(m_count);
    for (size_t m = 0; m < m_count; ++m) light[c][m] = cube_rgb[3 * m + c];
    RowTransform(ctx.params.row_filter, plan.light_res, light[c]);
  }
  absl::StatusOr<ZarrArray> staging =
      ZarrArray::Open(store::Path(traced, store::kStagingTransport));
  if (!staging.ok()) return staging.status();
  // B per staging cell (tile-major, JobPlan::StagingCell), summed in double
  // in a fixed order: groups, then columns, then cells.
  const size_t staged_cells = size_t(plan.tiles()) * plan.tile_cells();
  std::vector<double> b(3 * staged_cells, 0.0);
  std::vector<float> chunk(size_t(plan.group_size) * plan.tile_cells());
  for (int g = 0; g < plan.groups; ++g) {
    for (int t = 0; t < plan.tiles(); ++t) {
      const int64_t index[] = {g, t};
      if (absl::Status s = staging->ReadChunkInto(index, std::as_writable_bytes(std::span(chunk)));
          !s.ok())
        return s;
      double* out = &b[3 * size_t(t) * plan.tile_cells()];
      for (int c = 0; c < plan.GroupCount(g); ++c) {
        const size_t m = size_t(plan.GroupFirst(g)) + c;
        const float l[3] = {light[0][m], light[1][m], light[2][m]};
        if (l[0] == 0 && l[1] == 0 && l[2] == 0) continue;
        const float* column = &chunk[size_t(c) * plan.tile_cells()];
        for (int cell = 0; cell < plan.tile_cells(); ++cell) {
          const double v = column[cell];
          if (v == 0) continue;
          for (int k = 0; k < 3; ++k) out[3 * cell + k] += v * l[k];
        }
      }
    }
  }
  const SampleSet& samples = ctx.samples;
  std::vector<float> rgb(3 * size_t(samples.cells()), std::numeric_limits<float>::quiet_NaN());
  for (int y = 0; y < plan.height; ++y) {
    for (int x = 0; x < plan.width; ++x) {
      const int cell = y * plan.width + x;
      const int32_t id = samples.grid[cell];
      if (id < 0) continue;
      const int64_t at = plan.StagingCell(x, y);
      const Vec3 albedo = samples.albedo[id];
      for (int k = 0; k < 3; ++k)
        rgb[3 * size_t(cell) + k] = static_cast<float>(b[3 * at + k] * albedo[k]);
    }
  }
  return rgb;
}

}  // namespace wavebake::driver
