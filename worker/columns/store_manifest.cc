#include "worker/columns/store_manifest.h"

#include <string>

#include "core/bake/bake_params_io.h"
#include "storage/files/atomic_file.h"
#include "storage/store/params_json.h"
#include "storage/store/store_layout.h"
#include "storage/zarr/zarr_array.h"

namespace wavebake {
namespace {

// core/columns/quantizer.h, spelled out so that a reader without our code can decode.
constexpr char kDither[] =
    "u = DitherAt(seed, column, position): mix(z) = splitmix64 output step (z += "
    "0x9E3779B97F4A7C15; z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9; z = (z ^ (z >> 27)) * "
    "0x94D049BB133111EB; return z ^ (z >> 31)), uint64 wrapping; h = mix(mix(mix(seed) ^ "
    "column) ^ position); u = float32((h >> 40) * 2^-24 - 0.5)";
constexpr char kDequantize[] =
    "value = float32(ldexp((q - u) * scale, -s*l)) in float64, scale = the column's "
    "quantization step, s = 1 if level_scaling is 'paper' else 0, l = subband level of the "
    "position at the column's depth (0 = coarsest: the LL block and the details of the last "
    "step; details of step s have l = depth-1-s); scale 0 decodes to 0";

constexpr char kRefinedEntry[] =
    "texels decided by a uniform block: 0 if occluded, I_m = (1/pi) * integral over the texel "
    "of max(0, n.w) dw if visible (exact, Lambert's polygon formula); traced texels entirely "
    "above the horizon: I_m * sum_k V_k c_k / sum_k c_k; traced texels the horizon crosses: "
    "Omega_m / (K pi) * sum_{c_k > 0} V_k c_k (c_k = n.w_k, w_k the jittered directions)";
// The uv layout's atlas (core/layouts/uv_atlas.h): where each mesh's texels are,
// beside samples/uv_rects and samples/uv_domains.
nlohmann::json UvManifest(const BakeContext& ctx) {
  const SampleSet& s = ctx.samples;
  nlohmann::json meshes = nlohmann::json::array();
  for (const UvChart& c : s.uv_charts) {
    int64_t texels = 0;
    for (int y = c.y; y < c.y + c.height; ++y)
      for (int x = c.x; x < c.x + c.width; ++x) texels += s.grid[size_t(y) * s.width + x] >= 0;
    meshes.push_back({{"name", c.mesh},
                      {"rect", {c.x, c.y, c.width, c.height}},
                      {"domain", {c.u0, c.v0, c.u1, c.v1}},
                      {"texels", texels}});
  }
  return {{"channel", ctx.layout.uv_channel},
          {"fill", std::string(ToString(ctx.layout.fill))},
          {"allow_overlap", ctx.layout.allow_uv_overlap},
          {"covered_texels", s.size()},
          {"coverage", double(s.size()) / double(s.cells())},
          {"texel_convention",
           "texel (x, y) of the W×H lightmap covers u in [u0 + (x - rx)/rw·(u1 - u0), ...] of its "
           "mesh, row 0 at the top (v = v1); uv = (u0 + (x + 0.5 - rx)/rw·(u1 - u0), "
           "v1 - (y + 0.5 - ry)/rh·(v1 - v0)) at its centre, (rx, ry, rw, rh) the mesh's rect"},
          {"meshes", meshes}};
}

}  // namespace

nlohmann::json StoreManifest(const BakeContext& ctx, ManifestBits bits, nlohmann::json stats) {
  const BakeParams& p = ctx.params;
  nlohmann::json manifest = {{"format", store::kFormat},
                             {"scene", ctx.scene_spec},
                             {"scene_hash", ctx.scene_hash},
                             {"params", ToJson(p)},
                             {"layout", ToString(ctx.layout)},
                             {"N", p.light_res},
                             {"W", ctx.plan.width},
                             {"H", ctx.plan.height},
                             {"S", ctx.samples.size()},
                             {"M", ctx.plan.columns},
                             {"filters",
                              {{"row", std::string(ToString(p.row_filter))},
                               {"column", std::string(ToString(p.column_filter))}}},
                             {"bits", bits.bits},
                             {"level_scaling", std::string(ToString(p.level_scaling))},
                             {"bits_auto", p.bits == 0},
                             {"bits_needed", bits.bits_needed},
                             {"max_column_bits", bits.max_column_bits},
                             {"ray_epsilon", ctx.epsilon},
                             {"dither", kDither},
                             {"dequantize", kDequantize},
                             {"stats", std::move(stats)}};
  // Only a refined bake says so: a brute-force store keeps the bytes of
  // every store baked before refinement existed.
  if (ctx.refine) {
    const RefineOptions& o = ctx.refine->options();
    manifest["refinement"] = {{"start_spacing", o.start_spacing},
                              {"stagger", o.stagger},
                              {"follow", o.follow},
                              {"transport_entry", kRefinedEntry}};
  }
  if (ctx.layout.kind == LayoutKind::kUv) manifest["uv"] = UvManifest(ctx);
  // DESIGN.md §1 "What a row holds": said only when the rows are not the
  // diffuse T, so diffuse stores stay byte-identical to older ones.
  if (p.transport != Transport::kDiffuse)
    manifest["transport"] = std::string(ToString(p.transport));
  return manifest;
}

namespace {
int64_t ReadNnz(const std::filesystem::path& store) {
  absl::StatusOr<ZarrArray> a = ZarrArray::Open(store::Path(store, store::kIndices));
  return a.ok() ? a->spec().shape.at(0) : 0;
}
}  // namespace

uint64_t DirectoryBytes(const std::filesystem::path& dir) {
  uint64_t total = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir, ec)) {
    // A temp file is not the store's: another writer's (a stale worker of
    // FINALIZE whose lease expired) may appear at any time during the count.
    if (e.is_regular_file(ec) && !IsAtomicTempName(e.path().filename().string()))
      total += e.file_size(ec);
  }
  return total;
}

nlohmann::json StoreBytes(const BakeContext& ctx, const std::filesystem::path& store) {
  nlohmann::json arrays = nlohmann::json::object();
  uint64_t transport = 0;
  for (const char* name :
       {store::kIndptr, store::kIndices, store::kData, store::kDepth, store::kScale}) {
    const uint64_t n = DirectoryBytes(store::Path(store, name));
    arrays[name] = n;
    transport += n;
  }
  for (const char* name : {store::kGrid, store::kPosition, store::kNormal, store::kAlbedo,
                           store::kVertex, store::kUvRects, store::kUvDomains}) {
    if (std::filesystem::exists(store::Path(store, name)))
      arrays[name] = DirectoryBytes(store::Path(store, name));
  }
  const uint64_t raw = uint64_t(ctx.samples.size()) * uint64_t(ctx.plan.columns) * 4;
  // Bits per kept coefficient of each part of the sparse matrix: where the
  // bytes go, values against positions (docs/RESULTS.md chart 5).
  const double nnz = static_cast<double>(ReadNnz(store));
  const auto per = [&](const char* name) {
    return nnz > 0 ? 8.0 * arrays[name].get<double>() / nnz : 0.0;
  };
  return {{"arrays", arrays},
          {"bits_per_value", per(store::kData)},
          {"bits_per_position", per(store::kIndices)},
          {"transport", transport},
          {"raw_float32", raw},
          {"compression_ratio", transport > 0 ? double(raw) / double(transport) : 0.0}};
}

}  // namespace wavebake
