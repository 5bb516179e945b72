#include "worker/tiles/staging.h"

#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "storage/zarr/zarr_group.h"

namespace wavebake {

ArraySpec StagingTransportSpec(const JobPlan& plan) {
  ArraySpec spec;
  spec.shape = {plan.columns, int64_t{plan.width} * plan.height};
  spec.chunks = {plan.group_size, plan.tile_cells()};
  spec.dtype = DType::kFloat32;
  spec.fill_value = 0;
  spec.zstd_level = -3;
  return spec;
}

ArraySpec TileEnergySpec(const JobPlan& plan) {
  ArraySpec spec;
  spec.shape = {plan.tiles()};
  spec.chunks = {1};
  spec.dtype = DType::kFloat32;
  spec.fill_value = 0;
  return spec;
}

ArraySpec AuxTransportSpec(const JobPlan& plan) {
  ArraySpec spec = StagingTransportSpec(plan);
  spec.shape = {plan.columns, int64_t{plan.aux_tiles()} * plan.tile_cells()};
  return spec;
}

ArraySpec BounceEnergySpec(const JobPlan& plan) {
  ArraySpec spec;
  spec.shape = {plan.groups, plan.bounce_energies()};
  spec.chunks = {1, plan.bounce_energies()};
  spec.dtype = DType::kFloat32;
  spec.fill_value = 0;
  return spec;
}

absl::Status CreateStaging(const JobPlan& plan, const std::filesystem::path& store,
                           const nlohmann::json& trace) {
  // Groups first, so a Zarr reader sees the hierarchy (DESIGN.md §3).
  if (absl::Status s = WriteGroup(store); !s.ok()) return s;
  if (absl::Status s = WriteGroup(store::Path(store, store::kStaging)); !s.ok()) return s;
  if (!trace.is_null()) {
    if (absl::Status s = WriteAttrs(store::Path(store, store::kStaging), {{"trace", trace}});
        !s.ok())
      return s;
  }
  absl::StatusOr<ZarrArray> transport =
      ZarrArray::Create(store::Path(store, store::kStagingTransport), StagingTransportSpec(plan));
  if (!transport.ok()) return transport.status();
  if (plan.bounces > 0) {
    absl::StatusOr<ZarrArray> bounce =
        ZarrArray::Create(store::Path(store, store::kStagingBounceEnergy), BounceEnergySpec(plan));
    if (!bounce.ok()) return bounce.status();
  }
  if (plan.aux_samples > 0) {
    absl::StatusOr<ZarrArray> aux =
        ZarrArray::Create(store::Path(store, store::kStagingAuxTransport), AuxTransportSpec(plan));
    if (!aux.ok()) return aux.status();
  }
  return ZarrArray::Create(store::Path(store, store::kStagingTileEnergy), TileEnergySpec(plan))
      .status();
}

}  // namespace wavebake
