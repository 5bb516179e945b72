#include "worker/columns/column_bounces.h"

#include <algorithm>
#include <vector>

#include "absl/strings/str_cat.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/byte_buffer.h"
#include "storage/zarr/zarr_array.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

double BounceSumOfSquares(const float* v, size_t n) {
  double sum = 0;
  for (size_t i = 0; i < n; ++i) sum += double(v[i]) * v[i];
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
// (staging/aux_transport, or the job's in-memory staging): column c at
// aux[c·S_a, (c+1)·S_a). A chunk not written is a tile not baked, never zeros.
absl::Status AssembleAuxColumns(const JobPlan& plan, const std::filesystem::path& store, int group,
                                const MemoryStaging::Job* memory, std::span<float> aux) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kStagingAuxTransport));
  if (!a.ok()) return a.status();
  if (!SameSpec(a->spec(), AuxTransportSpec(plan)))
    return absl::FailedPreconditionError(
        absl::StrCat(a->dir().string(), ": does not match the job plan"));
  const size_t tile_cells = plan.tile_cells(), samples = plan.aux_samples;
  std::vector<float> chunk(size_t(plan.group_size) * tile_cells);
  for (int t = 0; t < plan.aux_tiles(); ++t) {
    std::span<const float> held =
        memory ? memory->Chunk(group, plan.tiles() + t) : std::span<const float>();
    if (held.empty()) {
      const int64_t index[2] = {group, t};
      if (!std::filesystem::exists(a->ChunkPath(index)))
        return absl::FailedPreconditionError(absl::StrCat(a->dir().string(), ": auxiliary tile ", t,
                                                          " (tile ", plan.tiles() + t,
                                                          ") has not been baked"));
      if (absl::Status s = a->ReadChunkInto(index, std::as_writable_bytes(std::span(chunk)));
          !s.ok())
        return s;
      held = chunk;
    }
    const size_t first = size_t(t) * tile_cells;
    const size_t n = std::min(tile_cells, samples - first);
    for (int c = 0; c < plan.GroupCount(group); ++c)
      std::copy_n(held.data() + size_t(c) * tile_cells, n, aux.data() + c * samples + first);
  }
  return absl::OkStatus();
}

bool BounceStopped(const TaskSignals& signals) {
  return signals.cancel != nullptr && signals.cancel->load(std::memory_order_relaxed);
}

// Cells per pass of Interleave: a pass's slice of the interleaved block
// (kSlice × n floats, 32 KB at n = 64) stays in L1 while each of the n
// columns is streamed into it, instead of one strided sweep over the whole
// block per column.
constexpr size_t kSlice = 128;

// Columns first..first+n of `images` (each `cells` long) into `block`,
// interleaved (block[cell·n + k] = column first+k).
void Interleave(std::span<const float> images, size_t cells, int first, int n,
                std::span<float> block) {
  for (size_t i0 = 0; i0 < cells; i0 += kSlice) {
    const size_t i1 = std::min(cells, i0 + kSlice);
    for (int k = 0; k < n; ++k) {
      const float* src = images.data() + size_t(first + k) * cells;
      for (size_t i = i0; i < i1; ++i) block[i * n + k] = src[i];
    }
  }
}

// Σ v² of each of the block's n interleaved vectors, in double, each over its
// cells in order.
void VectorEnergies(std::span<const float> block, size_t cells, int n, std::span<double> out) {
  std::fill_n(out.begin(), n, 0.0);
  for (size_t i = 0; i < cells; ++i)
    for (int k = 0; k < n; ++k) out[k] += double(block[i * n + k]) * block[i * n + k];
}

// The bounced light of columns first..first+n (interleaved in `block`) added
// to their images, but for a column whose bounced light holds no more than
// the truncation's threshold: that column keeps its direct light alone and
// the energy left out is recorded for its coding.
void AddOrLeaveOut(std::span<const float> block, size_t cells, int first, int n,
                   std::span<float> images, const BounceTruncation& truncation) {
  double e[BounceGather::kMaxBlock];
  VectorEnergies(block, cells, n, e);
  for (int k = 0; k < n; ++k) {
    if (e[k] <= truncation.threshold) {
      truncation.left_out[first + k] = e[k];
      continue;
    }
    float* dst = images.data() + size_t(first + k) * cells;
    for (size_t i = 0; i < cells; ++i) dst[i] += block[i * n + k];
  }
}

// Mesh and lightmap layouts: T_b = G T_{b−1} over the layout's own cells,
// BounceGather::kMaxBlock columns at a time (one pass over G's entries per
// block; the values of the columns side by side), their sum added to the
// images (AddOrLeaveOut).
absl::Status AddOwnBounces(const BounceGather& gather, const JobPlan& plan, int group,
                           std::span<float> images, std::vector<double>& energy,
                           const BounceTruncation& truncation, const TaskSignals& signals) {
  const size_t cells = size_t(plan.width) * plan.height;
  const int count = plan.GroupCount(group);
  std::vector<float> previous(cells * BounceGather::kMaxBlock), next(previous.size()),
      total(previous.size());
  double e[BounceGather::kMaxBlock];
  for (int first = 0; first < count; first += BounceGather::kMaxBlock) {
    if (BounceStopped(signals))
      return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
    const int n = std::min(BounceGather::kMaxBlock, count - first);
    for (int k = 0; k < n; ++k)
      energy[0] += BounceSumOfSquares(images.data() + size_t(first + k) * cells, cells);
    Interleave(images, cells, first, n, previous);
    std::fill_n(total.begin(), cells * n, 0.0f);
    for (int b = 1; b <= plan.bounces; ++b) {
      gather.ApplyBlock(previous, next, n);
      VectorEnergies(next, cells, n, e);
      for (int k = 0; k < n; ++k) energy[b] += e[k];
      for (size_t i = 0; i < cells * n; ++i) total[i] += next[i];
      previous.swap(next);
    }
    AddOrLeaveOut(total, cells, first, n, images, truncation);
  }
  return absl::OkStatus();
}

// AddAuxBounces' buffers, kept by the thread from group to group (a group's
// auxiliary columns alone are 37 MB on cubes-wall's camera: fresh pages each
// time cost a fault per page). Every element is written before it is read.
struct AuxScratch {
  DefaultInitVector<float> aux, previous, next, sum, bounce;
};
AuxScratch& ThreadAuxScratch() {
  thread_local AuxScratch scratch;
  return scratch;
}
std::span<float> Grown(DefaultInitVector<float>& v, size_t n) {
  if (v.size() < n) v.resize(n);
  return std::span(v).first(n);
}

// A camera layout: Σ_{b=1..B} T_b = G_ca Σ_{b<B} G_aa^b A₀ (core/bake/
// bake_gather.h): the bounces run over the auxiliary set, and the pixels
// gather their sum once, so B bounces cost B − 1 products with G_aa and one
// with G_ca. energy[b] is then that of the auxiliary set's bounce b,
// Σ (G_aa^b A₀)² for b < B (the record says so: G_aa^B A₀ is never formed),
// in blocks of columns as above.
absl::Status AddAuxBounces(const BakeGathers& gathers, const JobPlan& plan,
                           const std::filesystem::path& store, int group,
                           const MemoryStaging::Job* memory, std::span<float> images,
                           std::vector<double>& energy, const BounceTruncation& truncation,
                           const TaskSignals& signals) {
  const size_t cells = size_t(plan.width) * plan.height, samples = plan.aux_samples;
  const int count = plan.GroupCount(group);
  constexpr int kBlock = BounceGather::kMaxBlock;
  AuxScratch& scratch = ThreadAuxScratch();
  const std::span<float> aux = Grown(scratch.aux, size_t(count) * samples),
                         sum = Grown(scratch.sum, samples * kBlock),
                         bounce = Grown(scratch.bounce, cells * kBlock);
  std::span<float> previous = Grown(scratch.previous, samples * kBlock),
                   next = Grown(scratch.next, samples * kBlock);
  if (absl::Status s = AssembleAuxColumns(plan, store, group, memory, aux); !s.ok()) return s;
  for (int first = 0; first < count; first += kBlock) {
    if (BounceStopped(signals))
      return absl::CancelledError(absl::StrCat("group ", group, ": cancelled"));
    const int n = std::min(kBlock, count - first);
    for (int k = 0; k < n; ++k)
      energy[0] += BounceSumOfSquares(aux.data() + size_t(first + k) * samples, samples);
    Interleave(aux, samples, first, n, previous);
    if (plan.bounces > 1) std::copy_n(previous.begin(), samples * n, sum.begin());
    for (int b = 1; b < plan.bounces; ++b) {
      gathers.aux_gather->ApplyBlock(previous, next, n);
      for (int k = 0; k < n; ++k) {
        double e = 0;
        for (size_t i = 0; i < samples; ++i) e += double(next[i * n + k]) * next[i * n + k];
        energy[b] += e;
      }
      for (size_t i = 0; i < samples * n; ++i) sum[i] += next[i];
      std::swap(previous, next);
    }
    gathers.gather.ApplyBlock(plan.bounces == 1 ? previous : sum, bounce, n);
    AddOrLeaveOut(bounce, cells, first, n, images, truncation);
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status AddGroupBounces(const BakeContext& ctx, const std::filesystem::path& store, int group,
                             std::span<float> images, const BounceTruncation& truncation,
                             const TaskSignals& signals, const MemoryStaging::Job* memory) {
  const JobPlan& plan = ctx.plan;
  if (plan.bounces <= 0) return absl::OkStatus();
  if (!ctx.bounce)
    return absl::FailedPreconditionError("bounces: the context has no gather operator");
  if (truncation.left_out.size() != size_t(plan.GroupCount(group)))
    return absl::InvalidArgumentError("bounces: left_out is not one value per column of the group");
  std::vector<double> energy(plan.bounce_energies(), 0.0);
  absl::Status s = ctx.bounce->uses_aux() ? AddAuxBounces(*ctx.bounce, plan, store, group, memory,
                                                          images, energy, truncation, signals)
                                          : AddOwnBounces(ctx.bounce->gather, plan, group, images,
                                                          energy, truncation, signals);
  if (!s.ok()) return s;
  return WriteBounceEnergy(plan, store, group, energy);
}

}  // namespace wavebake
