#include "worker/columns/bounce_record.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

absl::StatusOr<std::vector<double>> ReadBounceEnergy(const JobPlan& plan,
                                                     const std::filesystem::path& store) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kStagingBounceEnergy));
  if (!a.ok()) return a.status();
  if (!SameSpec(a->spec(), BounceEnergySpec(plan)))
    return absl::FailedPreconditionError(
        absl::StrCat(a->dir().string(), ": does not match the job plan"));
  std::vector<double> energy(plan.bounce_energies(), 0.0);
  for (int64_t g = 0; g < plan.groups; ++g) {
    const int64_t index[2] = {g, 0};
    absl::StatusOr<std::vector<float>> row = a->ReadChunk<float>(index);
    if (!row.ok()) return row.status();
    for (size_t b = 0; b < energy.size(); ++b) energy[b] += (*row)[b];
  }
  return energy;
}

}  // namespace

absl::Status AddBounceRecord(const BakeContext& ctx, const std::filesystem::path& store,
                             nlohmann::json& manifest) {
  const JobPlan& plan = ctx.plan;
  if (plan.bounces > 0) {
    absl::StatusOr<std::vector<double>> energy = ReadBounceEnergy(plan, store);
    if (!energy.ok()) return energy.status();
    nlohmann::json ratio = nlohmann::json::array();
    for (double e : *energy) ratio.push_back((*energy)[0] > 0 ? std::sqrt(e / (*energy)[0]) : 0.0);
    manifest["bounces"] = {
        {"count", plan.bounces},
        {"gather_rays", ctx.bounce ? ctx.bounce->gather.rays : 0},
        {"gather_entries", ctx.bounce ? ctx.bounce->gather.entries() : 0},
        {"energy", *energy},
        {"rms_ratio", ratio},
        {"convention",
         "T = T_0 + ... + T_B, T_b(x) = 1/pi * integral of rho(y) T_{b-1}(y) max(0, n.w) dw over "
         "the first hits y (rho(y) = mean of y's RGB albedo; rho(x) factored out as for T_0); "
         "T_{b-1}(y) interpolated from the samples around y; energy[b] = sum of T_b^2 over the "
         "matrix, rms_ratio[b] = sqrt(energy[b] / energy[0])"}};
  } else if (ctx.auto_bounces) {
    manifest["bounces"] = {{"count", 0}};
  }
  if (ctx.bounce && ctx.bounce->uses_aux()) {
    const auto& rows = ctx.bounce->aux_rows;
    manifest["bounces"]["auxiliary"] = {
        {"kind", "vertices"},
        {"samples", plan.aux_samples},
        {"samples_traced", std::count(rows.begin(), rows.end(), uint8_t{1})},
        {"gather_entries", ctx.bounce->aux_gather ? ctx.bounce->aux_gather->entries() : 0},
        {"convention",
         "the camera's pixels gather bounced light from every vertex of the scene's meshes, in "
         "mesh order, whose direct rows A_0 were baked beside theirs: T = T_0 + G_ca sum_{b<B} "
         "G_aa^b A_0; only the samples_traced vertices that G_ca and B - 1 hops of G_aa reach "
         "have their rows traced (the others' are 0); bounces.energy[b] is then the vertices' "
         "sum of (G_aa^b A_0)^2, b = 0..B-1 (the light the pixels gather)"}};
  }
  if (ctx.auto_bounces) {
    manifest["bounces"]["auto"] = {
        {"estimate", ctx.auto_bounces->estimate},
        {"rule",
         "smallest B with estimate[B+1] <= target_error/2, estimate[b] = |G^b 1| / |1| over the "
         "samples (G one bounce's gather operator)"}};
  }
  return absl::OkStatus();
}

}  // namespace wavebake
