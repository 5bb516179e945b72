#include "worker/column_bounces.h"

#include <algorithm>
#include <vector>

#include "absl/strings/str_cat.h"
#include "storage/store_layout.h"
#include "storage/zarr_array.h"
#include "worker/staging.h"

namespace wavebake {
namespace {

double BounceSumOfSquares(std::span<const float> v) {
  double sum = 0;
  for (float x : v) sum += double(x) * x;
  return sum;
}

absl::Status WriteBounceEnergy(const JobPlan& plan, const std::filesystem::path& store, int group,
                               const std::vector<double>& energy) {
  // Idempotent (a recode's staging has no such array until its first group).
  absl::StatusOr<ZarrArray> a =
      ZarrArray::Create(store::Path(store, store::kStagingBounceEnergy), BounceEnergySpec(plan));
  if (!a.ok()) return a.status();
  const std::vector<float> row(energy.begin(), energy.end());
  const int64_t index[2] = {group, 0};
  return a->WriteChunk<float>(index, row);
}

// The group's columns of the auxiliary samples' direct rows A₀
// (staging/aux_transport): column c at aux[c·S_a, (c+1)·S_a). A chunk not
// written is a tile not baked, never zeros.
absl::Status AssembleAuxColumns(const JobPlan& plan, const std::filesystem::path& store, int group,
                                std::span<float> aux) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kStagingAuxTransport));
  if (!a.ok()) return a.status();
  if (!SameSpec(a->spec(), AuxTransportSpec(plan)))
    return absl::FailedPreconditionError(
        absl::StrCat(a->dir().string(), ": does not match the job plan"));
  const size_t tile_cells = plan.tile_cells(), samples = plan.aux_samples;
  std::vector<float> chunk(size_t(plan.group_size) * tile_cells);
  for (int t = 0; t < plan.aux_tiles(); ++t) {
    const int64_t index[2] = {group, t};
    if (!std::filesystem::exists(a->ChunkPath(index)))
      return absl::FailedPreconditionError(absl::StrCat(a->dir().string(), ": auxiliary tile ", t,
                                                        " (tile ", plan.tiles() + t,
                                                        ") has not been baked"));
    if (absl::Status s = a->ReadChunkInto(index, std::as_writable_bytes(std::span(chunk))); !s.ok())
      return s;
    const size_t first = size_t(t) * tile_cells;
    const size_t n = std::min(tile_cells, samples - first);
    for (int c = 0; c < plan.GroupCount(group); ++c)
      std::copy_n(chunk.data() + size_t(c) * tile_cells, n, aux.data() + c * samples + first);
  }
  return absl::OkStatus();
}

bool BounceStopped(const TaskSignals& signals) {
  return signals.cancel != nullptr && signals.cancel->load(std::memory_order_relaxed);
}

// Mesh and lightmap layouts: T_b = G T_{b−1} over the layout's own cells.
absl::Status AddOwnBounces(const BounceGather& gather, const JobPlan& plan, int group,
                           std::span<float> images, std::vector<double>& energy,
                           const TaskSignals& signals) {
  const size_t cells = size_t(plan.width) * plan.height;
  std::vector<float> previous(cells), next(cells);
  for (int c = 0; c < plan.GroupCount(group); ++c) {
    if (BounceStopped(signals))
      return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
    const std::span<float> image = images.subspan(c * cells, cells);
    energy[0] += BounceSumOfSquares(image);
    std::copy(image.begin(), image.end(), previous.begin());
    for (int b = 1; b <= plan.bounces; ++b) {
      gather.Apply(previous, next);
      energy[b] += BounceSumOfSquares(next);
      for (size_t i = 0; i < cells; ++i) image[i] += next[i];
      previous.swap(next);
    }
  }
  return absl::OkStatus();
}

// A camera layout: T_b = G_ca G_aa^{b−1} A₀ (core/bake/bake_gather.h).
absl::Status AddAuxBounces(const BakeGathers& gathers, const JobPlan& plan,
                           const std::filesystem::path& store, int group, std::span<float> images,
                           std::vector<double>& energy, const TaskSignals& signals) {
  const size_t cells = size_t(plan.width) * plan.height, samples = plan.aux_samples;
  std::vector<float> aux(size_t(plan.GroupCount(group)) * samples);
  if (absl::Status s = AssembleAuxColumns(plan, store, group, aux); !s.ok()) return s;
  std::vector<float> previous(samples), next(samples), bounce(cells);
  for (int c = 0; c < plan.GroupCount(group); ++c) {
    if (BounceStopped(signals))
      return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
    const std::span<float> image = images.subspan(c * cells, cells);
    energy[0] += BounceSumOfSquares(image);
    std::copy_n(aux.begin() + c * samples, samples, previous.begin());
    for (int b = 1; b <= plan.bounces; ++b) {
      gathers.gather.Apply(previous, bounce);
      energy[b] += BounceSumOfSquares(bounce);
      for (size_t i = 0; i < cells; ++i) image[i] += bounce[i];
      if (b == plan.bounces) break;
      gathers.aux_gather->Apply(previous, next);
      previous.swap(next);
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status AddGroupBounces(const BakeContext& ctx, const std::filesystem::path& store, int group,
                             std::span<float> images, const TaskSignals& signals) {
  const JobPlan& plan = ctx.plan;
  if (plan.bounces <= 0) return absl::OkStatus();
  if (!ctx.bounce)
    return absl::FailedPreconditionError("bounces: the context has no gather operator");
  std::vector<double> energy(plan.bounces + 1, 0.0);
  absl::Status s = ctx.bounce->aux_gather
                       ? AddAuxBounces(*ctx.bounce, plan, store, group, images, energy, signals)
                       : AddOwnBounces(ctx.bounce->gather, plan, group, images, energy, signals);
  if (!s.ok()) return s;
  return WriteBounceEnergy(plan, store, group, energy);
}

}  // namespace wavebake
