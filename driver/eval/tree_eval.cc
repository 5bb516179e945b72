#include "driver/eval/tree_eval.h"

#include <chrono>
#include <cmath>
#include <cstring>

#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "driver/relight/tree_export.h"
#include "runtime/gpu/wavelet_tree_reader.h"
#include "runtime/relight/lighting.h"
#include "runtime/relight/store_relight.h"

namespace wavebake::driver {
namespace {

// The trees of `t` relit by their reader under `lights`.
absl::StatusOr<std::vector<float>> TreeImage(const WaveletTreeTextures& t,
                                             const WaveletLights& lights) {
  std::vector<uint8_t> blocks(t.blocks.size() * 4), cells(t.cells.size() * 4);
  std::memcpy(blocks.data(), t.blocks.data(), blocks.size());
  std::memcpy(cells.data(), t.cells.data(), cells.size());
  absl::StatusOr<WaveletTreeReader> reader = WaveletTreeReader::Parse(
      WaveletTreeHeader(t, {}), t.line, std::move(blocks), std::move(cells));
  if (!reader.ok()) return reader.status();
  std::vector<float> dense(3 * 6 * size_t(t.light_res) * t.light_res, 0.0f);
  for (const WaveletLight& l : lights.lights)
    for (int c = 0; c < 3; ++c) dense[3 * size_t(l.column) + c] = l.weight[c];
  return reader->Relight(dense);
}

}  // namespace

absl::StatusOr<TreeEvalReport> EvaluateTrees(const std::filesystem::path& store,
                                             std::string_view env_spec, int terms,
                                             const EvalOptions& options,
                                             const std::vector<WaveletTreeOptions>& settings) {
  absl::StatusOr<EnvMap> env_map = LoadEnvMap(env_spec);
  if (!env_map.ok()) return env_map.status();
  const EnvMap env =
      options.rotate_degrees != 0 ? Rotated(*env_map, options.rotate_degrees) : *env_map;
  absl::StatusOr<TreeSource> source = OpenTreeSource(store);
  if (!source.ok()) return source.status();
  absl::StatusOr<OpenedStore> opened = OpenStore(store);
  if (!opened.ok()) return opened.status();
  absl::StatusOr<RayCaster> caster = BuildBakedScene(opened->info);
  if (!caster.ok()) return caster.status();
  ReferenceOptions ref_options = options.reference;
  ref_options.epsilon = BakedEpsilon(opened->info, *caster);
  absl::StatusOr<LightingCoefficients> lighting =
      LightingFromEnv(env, opened->relighter.light_res(), WaveletFilter::kHaar);
  if (!lighting.ok()) return lighting.status();
  absl::StatusOr<WaveletLights> lights = SelectWaveletLights(*lighting, terms);
  if (!lights.ok()) return lights.status();

  TreeEvalReport out;
  // One reference for the store and every setting (CompareWithReference's
  // fields, without the dense retrace).
  absl::StatusOr<ReferenceResult> ref =
      ComputeReference(*caster, opened->samples, env, ref_options);
  if (!ref.ok()) return ref.status();
  out.store.terms = terms;
  out.store.reference_rel_se = ref->rel_se;
  out.store.reference_rays = ref->rays;
  out.store.reference_seconds = ref->seconds;
  out.store.reference_converged = ref->converged;
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<std::vector<float>> image = RelightImage(*opened, env, terms);
  if (!image.ok()) return image.status();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  absl::StatusOr<ErrorStats> e = CompareFinite(*image, ref->rgb, "the compressed relighting");
  if (!e.ok()) return e.status();
  out.store.compressed = *e;
  out.store.compressed.seconds = seconds;
  for (const WaveletTreeOptions& o : settings) {
    absl::StatusOr<WaveletTreeTextures> t = WaveletTreesOf(*source, o);
    if (!t.ok()) return t.status();
    absl::StatusOr<std::vector<float>> image = TreeImage(*t, *lights);
    if (!image.ok()) return image.status();
    absl::StatusOr<ErrorStats> e = CompareFinite(*image, ref->rgb, "the trees' relighting");
    if (!e.ok()) return e.status();
    out.trees.push_back(
        {.asked = o,
         .cut_off = t->cut_off,
         .code_bits = t->code_bits,
         .bytes = static_cast<int64_t>(t->bytes()),
         .trees = t->stats.trees,
         .nodes_kept = t->stats.nodes_kept,
         .nodes_total = t->stats.nodes_total,
         .jumps = t->stats.jumps,
         .rel_error_pruned = t->stats.energy_total > 0
                                 ? std::sqrt(t->stats.energy_pruned / t->stats.energy_total)
                                 : 0.0,
         .rel_error_quantized = t->stats.energy_total > 0
                                    ? std::sqrt(t->stats.energy_quantized / t->stats.energy_total)
                                    : 0.0,
         .error = *e});
  }
  return out;
}

nlohmann::json TreeEvalJson(const TreeEvalReport& r) {
  nlohmann::json j = EvalReportJson(r.store);
  nlohmann::json rows = nlohmann::json::array();
  for (const TreeEvalRow& t : r.trees) {
    nlohmann::json row = {{"cut_off", t.cut_off},
                          {"level_weight", t.asked.level_weight},
                          {"code_bits", t.code_bits},
                          {"bytes", t.bytes},
                          {"trees", t.trees},
                          {"nodes_kept", t.nodes_kept},
                          {"nodes_total", t.nodes_total},
                          {"jumps", t.jumps},
                          {"rel_error_pruned", t.rel_error_pruned},
                          {"rel_error_quantized", t.rel_error_quantized},
                          {"rel_rms", t.error.rel_rms},
                          {"max_abs", t.error.max_abs},
                          {"psnr", std::isfinite(t.error.psnr) ? nlohmann::json(t.error.psnr)
                                                               : nlohmann::json(nullptr)}};
    row["target_error"] =
        t.asked.cut_off < 0 ? nlohmann::json(t.asked.target_error) : nlohmann::json(nullptr);
    rows.push_back(row);
  }
  j["trees"] = rows;
  return j;
}

std::string TreeEvalText(const TreeEvalReport& r) {
  std::string text = EvalReportText(r.store);
  for (const TreeEvalRow& t : r.trees)
    text += absl::StrFormat(
        "trees cut-off %.4g @%g (bits %s): rel_rms %.5f  max_abs %.5g  psnr %6.2f dB  %lld bytes  "
        "%.2f%% of nodes kept\n",
        t.cut_off, t.asked.level_weight, absl::StrJoin(t.code_bits, ","), t.error.rel_rms,
        t.error.max_abs, t.error.psnr, static_cast<long long>(t.bytes),
        t.nodes_total > 0 ? 100.0 * double(t.nodes_kept) / double(t.nodes_total) : 0.0);
  return text;
}

}  // namespace wavebake::driver
