#include "worker/tiles/row_reuse.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <map>
#include <optional>
#include <unordered_map>

#include "absl/strings/str_cat.h"
#include "core/scene/scene_diff.h"
#include "core/util/parallel_for.h"
#include "storage/scene_files/scene_loader.h"
#include "storage/store/params_json.h"
#include "storage/store/store_layout.h"
#include "storage/store/store_reader.h"
#include "storage/zarr/zarr_array.h"
#include "storage/zarr/zarr_group.h"
#include "worker/tiles/bake_context.h"
#include "worker/tiles/row_transform.h"
#include "worker/tiles/staging.h"

namespace wavebake {
namespace {

absl::Status Refuse(const std::filesystem::path& old_store, const auto&... why) {
  return absl::FailedPreconditionError(absl::StrCat("update: ", old_store.string(), ": ", why...));
}

// Most cone texels a patched row may have (RowReuse::patch).
constexpr int kPatchTexels = 256;

// A sample by the bits of its position and normal: equal keys trace equal rows.
using SampleKey = std::array<uint32_t, 6>;
struct SampleKeyHash {
  size_t operator()(const SampleKey& k) const {
    uint64_t h = 0x9E3779B97F4A7C15ull;
    for (uint32_t v : k) h = (h ^ v) * 0x100000001B3ull;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};
SampleKey KeyOf(Vec3 p, Vec3 n) {
  return {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z),
          std::bit_cast<uint32_t>(n.x), std::bit_cast<uint32_t>(n.y), std::bit_cast<uint32_t>(n.z)};
}

// Old sample id -> its column on the old staging array's second axis.
std::vector<int64_t> StagingColumns(const SampleSet& s, const JobPlan& plan) {
  std::vector<int64_t> column(s.size(), -1);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      if (const int32_t id = s.grid[size_t(y) * s.width + x]; id >= 0)
        column[id] = plan.StagingCell(x, y);
  return column;
}

absl::StatusOr<Scene> OldScene(const StoreInfo& info, const OldStore& old) {
  const std::filesystem::path& old_store = old.path;
  const std::string& spec = old.scene.empty() ? info.scene_spec : old.scene;
  absl::StatusOr<Scene> scene = LoadScene(spec, nullptr, old.scene_files.get());
  if (!scene.ok())
    return Refuse(old_store, "its scene '", info.scene_spec,
                  "' is needed (the old placement of what changed bounds the rows to rebake) "
                  "and does not load: ",
                  scene.status().message());
  if (StoreSceneHash(info, *scene) != info.scene_hash)
    return Refuse(old_store, "its scene '", info.scene_spec,
                  "' has changed since the store was baked (scene hash ",
                  StoreSceneHash(info, *scene), ", the store's ", info.scene_hash,
                  "): keep the old scene file to update from the store");
  return scene;
}

void MarkRows(const BakeContext& ctx, const std::vector<int64_t>& old_column,
              const std::unordered_map<SampleKey, int32_t, SampleKeyHash>& old_ids,
              const DirtyRowTest* dirty, RowReuse& r) {
  const SampleSet& s = ctx.samples;
  std::vector<int64_t> by_sample(s.size(), -1);
  std::vector<uint8_t> unmatched(s.size(), 0), patch(s.size(), 0);
  std::vector<DirtyRowStats> stats(s.size() == 0 ? 1 : 64);
  const int chunk = std::max(1, (s.size() + 63) / 64);
  ParallelFor(static_cast<int>(stats.size()), [&](int c) {
    for (int id = c * chunk; id < std::min(s.size(), (c + 1) * chunk); ++id) {
      auto it = old_ids.find(KeyOf(s.position[id], s.normal[id]));
      if (it == old_ids.end()) {
        unmatched[id] = 1;
        continue;
      }
      if (dirty && dirty->MayChange(s.position[id], s.normal[id], ctx.epsilon, &stats[c])) {
        // A patch traces single rays through its cones against the two
        // placements; past kPatchTexels it costs more than the refined row
        // (~1400 packet rays per row of the N=32 bench bakes): traced
        // instead. Measured on those bakes (bench/update_bake.sh): the
        // update's CPU falls from 32 to 128 texels and is flat from 256 to 512.
        if (!r.delta ||
            r.delta->TexelsInCones(s.position[id], s.normal[id], ctx.epsilon) > kPatchTexels)
          continue;
        patch[id] = 1;
      }
      by_sample[id] = old_column[it->second];
    }
  });
  for (const DirtyRowStats& d : stats) {
    r.dirty.texels_in_cones += d.texels_in_cones;
    r.dirty.rays_changed += d.rays_changed;
    r.dirty.rays_static += d.rays_static;
  }
  for (size_t cell = 0; cell < s.grid.size(); ++cell) {
    const int32_t id = s.grid[cell];
    if (id < 0) continue;
    r.source[cell] = by_sample[id];
    if (patch[id]) {
      if (r.patch.empty()) r.patch.assign(s.grid.size(), 0);
      r.patch[cell] = 1;
      ++r.patched;
    }
    r.reused += by_sample[id] >= 0 && !patch[id];
    r.unmatched += unmatched[id];
  }
  r.rebaked = r.samples - r.reused - r.patched;
}

// The old store's hilbert grid with its sample ids (global vertex ids, the
// meshes concatenated in order) renamed to the new scene's: an unchanged
// mesh maps to its partner, a removed one to the first added one of its
// name and vertex count (a moved mesh). Nothing if a mesh of either scene
// has no counterpart, or the old grid is not over vertex ids.
std::optional<std::vector<int32_t>> KeptHilbertGrid(const SampleSet& old, const Scene& old_scene,
                                                    const Scene& new_scene, const SceneDiff& diff,
                                                    const SampleSet& now) {
  const size_t n_old = old_scene.meshes.size();
  std::vector<int> to(n_old, -1);
  for (const auto& [i, j] : diff.unchanged) to[i] = j;
  std::vector<bool> taken(new_scene.meshes.size(), false);
  for (int i : diff.removed)
    for (int j : diff.added)
      if (!taken[j] && new_scene.meshes[j].name == old_scene.meshes[i].name &&
          new_scene.meshes[j].positions.size() == old_scene.meshes[i].positions.size()) {
        to[i] = j;
        taken[j] = true;
        break;
      }
  for (int j : diff.added)
    if (!taken[j]) return std::nullopt;
  std::vector<int32_t> new_offset(new_scene.meshes.size() + 1, 0), rename;
  for (size_t j = 0; j < new_scene.meshes.size(); ++j)
    new_offset[j + 1] = new_offset[j] + static_cast<int32_t>(new_scene.meshes[j].positions.size());
  for (size_t i = 0; i < n_old; ++i) {
    if (to[i] < 0) return std::nullopt;
    for (size_t k = 0; k < old_scene.meshes[i].positions.size(); ++k)
      rename.push_back(new_offset[to[i]] + static_cast<int32_t>(k));
  }
  if (old.vertex.size() != rename.size() || now.size() != static_cast<int>(rename.size()) ||
      old.grid.size() != now.grid.size())
    return std::nullopt;
  std::vector<int32_t> grid(old.grid.size(), -1);
  for (size_t c = 0; c < grid.size(); ++c)
    if (const int32_t id = old.grid[c]; id >= 0) grid[c] = rename[old.vertex[id]];
  return grid;
}

// in_place and tile_touched of RowReuse, from the old grid.
void MarkTiles(const SampleSet& now, const SampleSet& old, const JobPlan& plan, RowReuse& r) {
  r.tile_touched.assign(plan.tiles(), 0);
  r.in_place = now.width == old.width && now.height == old.height;
  if (!r.in_place) return;
  for (int y = 0; y < now.height; ++y)
    for (int x = 0; x < now.width; ++x) {
      const size_t cell = size_t(y) * now.width + x;
      const int64_t src = r.source[cell], at = plan.StagingCell(x, y);
      const bool was = old.grid[cell] >= 0, is = now.grid[cell] >= 0;
      if (src >= 0 && src != at) r.in_place = false;
      const bool patched = !r.patch.empty() && r.patch[cell];
      if ((is && src < 0) || was != is || patched) r.tile_touched[at / plan.tile_cells()] = 1;
    }
}

// The inverse of BAKE_TILE's blocked transpose: chunk [count, cells] (column
// j of the group over the old tile contiguous) into the rows of `pairs`
// (cell of this tile, cell of the old tile), columns [first, first + count).
// Sixteen columns at a time: a row's sixteen writes fill one cache line, and
// the sixteen chunk rows read advance together through the old tile, where
// one column after another would touch a new line of the chunk per value.
void CopyStagedRows(std::span<const float> chunk, size_t cells,
                    std::span<const std::pair<int, int>> pairs, int first, int count,
                    std::span<float> rows, size_t stride) {
  for (int j0 = 0; j0 < count; j0 += 16) {
    const int width = std::min(16, count - j0);
    const float* in = chunk.data() + size_t(j0) * cells;
    for (const auto& [cell, at] : pairs) {
      float* out = rows.data() + size_t(cell) * stride + first + j0;
      for (int j = 0; j < width; ++j) out[j] = in[size_t(j) * cells + at];
    }
  }
}

}  // namespace

nlohmann::json RowReuse::Record() const {
  nlohmann::json j = {{"from", from},
                      {"mode", exact ? "exact" : "local"},
                      {"rows", samples},
                      {"rows_reused", reused},
                      {"rows_patched", patched},
                      {"patch_max_texels", kPatchTexels},
                      {"layout", kept_layout ? "the old store's cells (moved meshes keep theirs)"
                                             : "this bake's own"},
                      {"rows_rebaked", rebaked},
                      {"rows_unmatched", unmatched},
                      {"changed_meshes", changed_meshes},
                      {"albedo_meshes", albedo_meshes},
                      {"dirty_test",
                       {{"texels_in_cones", dirty.texels_in_cones},
                        {"rays_changed", dirty.rays_changed},
                        {"rays_static", dirty.rays_static},
                        {"seconds", plan_seconds}}}};
  if (!full_reason.empty()) j["full_bake"] = full_reason;
  return j;
}

absl::Status CheckUpdateSource(const std::filesystem::path& old_store, const BakeParams& params) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(old_store);
  if (!info.ok())
    return Refuse(old_store, "--update needs a finished store: ", info.status().message());
  const std::filesystem::path staging = store::Path(old_store, store::kStaging);
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(staging);
  if (!std::filesystem::is_directory(store::Path(old_store, store::kStagingTransport)) ||
      !attrs.ok() || !attrs->contains("trace"))
    return Refuse(old_store,
                  "keeps no staged rows to reuse; bake it with --keep-staging to update it later");
  // Every recorded parameter but the scene, in the record's (sorted) order.
  if (const std::string differs = FirstParameterDifference(info->attrs["params"], ToJson(params));
      !differs.empty())
    return Refuse(old_store, differs);
  return absl::OkStatus();
}

absl::Status CheckOldScene(const std::filesystem::path& old_store) {
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(old_store);
  if (!info.ok()) return info.status();
  OldStore old;
  old.path = old_store;
  return OldScene(*info, old).status();
}

absl::StatusOr<std::shared_ptr<const RowReuse>> PlanRowReuse(BakeContext& ctx, const OldStore& old,
                                                             bool exact) {
  const std::filesystem::path& old_store = old.path;
  const auto start = std::chrono::steady_clock::now();
  if (absl::Status s = CheckUpdateSource(old_store, ctx.params); !s.ok()) return s;
  absl::StatusOr<StoreInfo> info = ReadStoreInfo(old_store);
  if (!info.ok()) return info.status();
  absl::StatusOr<ZarrArray> staged =
      ZarrArray::Open(store::Path(old_store, store::kStagingTransport));
  if (!staged.ok()) return staged.status();
  if (!SameSpec(staged->spec(), StagingTransportSpec(ctx.plan)))
    return Refuse(old_store, "its staging array is not laid out as this bake's (grid ", info->width,
                  "x", info->height, ", this one ", ctx.plan.width, "x", ctx.plan.height, ")");
  absl::StatusOr<SampleSet> old_samples = ReadSamples(old_store);
  if (!old_samples.ok()) return old_samples.status();
  absl::StatusOr<nlohmann::json> trace = ReadAttrs(store::Path(old_store, store::kStaging));
  if (!trace.ok()) return trace.status();
  absl::StatusOr<Scene> old_scene = OldScene(*info, old);
  if (!old_scene.ok()) return old_scene.status();

  auto r = std::make_shared<RowReuse>();
  r->old_store = old_store;
  r->from = old.recorded;
  r->exact = exact;
  r->samples = ctx.samples.size();
  r->source.assign(ctx.samples.grid.size(), -1);
  const SceneDiff diff = DiffScenes(*old_scene, ctx.scene);
  // Keeping the old cells keeps rows in place for the local column stage.
  // With bounces every column is coded anew, and the gather operators were
  // built over this bake's own cells (worker/tiles/bake_context.h), so the
  // cells must stay as they are.
  if (!exact && ctx.plan.bounces == 0 && ctx.layout.kind == LayoutKind::kHilbert) {
    if (std::optional<std::vector<int32_t>> grid =
            KeptHilbertGrid(*old_samples, *old_scene, ctx.scene, diff, ctx.samples)) {
      ctx.samples.grid = *std::move(grid);
      r->kept_layout = true;
    }
  }
  for (int i : diff.removed) r->changed_meshes.push_back(old_scene->meshes[i].name);
  for (int j : diff.added) r->changed_meshes.push_back(ctx.scene.meshes[j].name);
  for (int j : diff.albedo_changed) r->albedo_meshes.push_back(ctx.scene.meshes[j].name);
  if (diff.camera_changed && ctx.layout.kind == LayoutKind::kCamera)
    r->full_reason = "the camera moved: every camera sample is another point (a full bake)";
  else if ((*trace)["trace"].value("ray_epsilon", nlohmann::json()) != nlohmann::json(ctx.epsilon))
    r->full_reason =
        "the ray offset (1e-4 of the scene's bounding-box diagonal) changed with the box: "
        "every row is rebaked";
  if (r->full_reason.empty()) {
    std::unordered_map<SampleKey, int32_t, SampleKeyHash> old_ids;
    for (int id = 0; id < old_samples->size(); ++id)
      old_ids.emplace(KeyOf(old_samples->position[id], old_samples->normal[id]), id);
    std::optional<DirtyRowTest> dirty;
    if (diff.geometry_changed()) {
      absl::StatusOr<DirtyRowTest> test =
          DirtyRowTest::Build(ChangedGeometry(*old_scene, ctx.scene, diff),
                              UnchangedGeometry(ctx.scene, diff), ctx.jitter);
      if (!test.ok()) return test.status();
      dirty.emplace(*std::move(test));
      // --update patches the rows the edit reaches (brute-force difference,
      // diffuse T on the cube only); --update-exact traces them.
      if (!exact && ctx.params.transport == Transport::kDiffuse &&
          !ctx.params.light_domain.is_plane()) {
        auto delta = std::make_shared<DirtyRowTest>(*dirty);
        if (absl::Status s = delta->SetPlacements(RemovedGeometry(*old_scene, diff),
                                                  AddedGeometry(ctx.scene, diff));
            !s.ok())
          return s;
        r->delta = std::move(delta);
      }
    }
    MarkRows(ctx, StagingColumns(*old_samples, ctx.plan), old_ids, dirty ? &*dirty : nullptr, *r);
  } else {
    r->rebaked = r->samples;
  }
  MarkTiles(ctx.samples, *old_samples, ctx.plan, *r);
  r->plan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

absl::StatusOr<int> FillReusedRows(const RowReuse& reuse, const JobPlan& plan, int tile,
                                   std::span<float> rows, size_t stride,
                                   std::vector<uint8_t>& filled, OldRows* rewritten) {
  const TileRect rect = plan.Tile(tile);
  filled.assign(plan.tile_cells(), 0);
  auto patched = [&](int cell) {
    const size_t grid =
        size_t(rect.y0 + cell / rect.width) * plan.width + rect.x0 + cell % rect.width;
    return !reuse.patch.empty() && reuse.patch[grid];
  };
  // Old tile -> (cell of this tile, cell inside the old tile).
  std::map<int64_t, std::vector<std::pair<int, int>>> wanted;
  // In place, the old tile is this one: (k, cell) for the old rows of the
  // cells traced or masked, into rewritten->values row k.
  std::vector<std::pair<int, int>> old_rows;
  for (int cy = 0; cy < rect.height; ++cy)
    for (int cx = 0; cx < rect.width; ++cx) {
      const int cell = cy * rect.width + cx;
      const int64_t src = reuse.source[size_t(rect.y0 + cy) * plan.width + rect.x0 + cx];
      if (src >= 0)
        wanted[src / plan.tile_cells()].emplace_back(cell,
                                                     static_cast<int>(src % plan.tile_cells()));
      if (rewritten != nullptr && src < 0)
        old_rows.emplace_back(static_cast<int>(old_rows.size()), cell);
    }
  if (rewritten != nullptr) {
    rewritten->cells.clear();
    for (const auto& [k, cell] : old_rows) rewritten->cells.push_back(cell);
    // Room for a whole tile at once, so that a thread's buffer is not
    // reallocated (and first-touched again) as its tiles need more.
    rewritten->values.reserve(size_t(plan.tile_cells()) * plan.columns);
    rewritten->values.resize(old_rows.size() * plan.columns);
    if (!old_rows.empty()) wanted[tile];  // read even if no row is reused
  }
  if (wanted.empty()) return 0;
  absl::StatusOr<ZarrArray> staged =
      ZarrArray::Open(store::Path(reuse.old_store, store::kStagingTransport));
  if (!staged.ok()) return staged.status();
  const size_t cells = plan.tile_cells();
  int count = 0;
  for (const auto& [old_tile, pairs] : wanted) {
    for (int g = 0; g < plan.groups; ++g) {
      const int64_t index[] = {g, old_tile};
      absl::StatusOr<std::vector<float>> chunk = staged->ReadChunk<float>(index);
      if (!chunk.ok()) return chunk.status();
      CopyStagedRows(*chunk, cells, pairs, plan.GroupFirst(g), plan.GroupCount(g), rows, stride);
      if (old_tile == tile && !old_rows.empty())
        CopyStagedRows(*chunk, cells, old_rows, plan.GroupFirst(g), plan.GroupCount(g),
                       rewritten->values, plan.columns);
    }
    for (const auto& [cell, at] : pairs) filled[cell] = patched(cell) ? 2 : 1;
    count += static_cast<int>(pairs.size());
  }
  return count;
}

void PatchRow(const RowReuse& reuse, const BakeContext& ctx, int32_t id, std::span<float> row,
              std::span<uint8_t> changed) {
  thread_local std::vector<float> delta;
  delta.resize(row.size());
  if (!reuse.delta->RowDelta(ctx.samples.position[id], ctx.samples.normal[id], ctx.epsilon, delta,
                             nullptr))
    return;
  // The row transform is linear: transform(old + Δ) = staged old + transform(Δ).
  RowTransform(ctx.params.row_filter, ctx.plan.light_res, delta);
  if (changed.empty()) {
    for (size_t m = 0; m < row.size(); ++m) row[m] += delta[m];
    return;
  }
  // Restrict: `changed` is bytes, which may alias anything, and would
  // otherwise keep the loop from being vectorized.
  float* __restrict out = row.data();
  const float* __restrict add = delta.data();
  uint8_t* __restrict mark = changed.data();
  for (size_t m = 0; m < row.size(); ++m) {
    const uint32_t was = std::bit_cast<uint32_t>(out[m]);
    out[m] += add[m];
    mark[m] |= static_cast<uint8_t>(std::bit_cast<uint32_t>(out[m]) != was);
  }
}

bool CodesChangedColumnsOnly(const BakeContext& ctx) {
  return StartsFromOldCodings(ctx) && ctx.plan.bounces == 0;
}

bool StartsFromOldCodings(const BakeContext& ctx) { return ctx.reuse && !ctx.reuse->exact; }

absl::Status WriteUpdateRecord(const std::filesystem::path& store, const RowReuse& reuse,
                               int64_t columns_recomputed, int64_t columns_searched,
                               int64_t columns, int bounces) {
  absl::StatusOr<nlohmann::json> attrs = ReadAttrs(store);
  if (!attrs.ok()) return attrs.status();
  nlohmann::json record = reuse.Record();
  record["columns"] = columns;
  record["columns_recomputed"] = columns_recomputed;
  record["columns_depth_searched"] = columns_searched;
  record["bounces"] = bounces;
  record["column_decisions"] =
      reuse.exact ? "every column coded anew from the merged rows, as a full bake"
      : bounces > 0
          ? "every column coded anew from the updated direct rows and the bounces gathered "
            "over the new scene (bounced light reaches every sample), at its old depth "
            "unless it kept nothing before or its energy moved by over a quarter"
          : "columns whose values changed in a tile with a rebaked cell: selected "
            "against the new matrix energy at their old depth (the adaptive depth "
            "searched again if they kept nothing before or their energy moved by over "
            "a quarter); the others keep the old depth and selection; one matrix-wide "
            "quantization step over all (FINALIZE)";
  (*attrs)["update"] = std::move(record);
  return WriteAttrs(store, *attrs);
}

}  // namespace wavebake
