// `wavebake eval OUT.wbk --env ENV --reference [--terms n] [--json]`
// (DESIGN.md §5): the store's relighting error, and the uncompressed T's,
// against an independently traced Monte-Carlo reference (runtime/reference/eval.h);
// with --area-light, near-field lights over their area (runtime/reference/area_eval.h).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include "absl/strings/numbers.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/shading_flags.h"
#include "driver/eval/evaluate.h"
#include "driver/eval/tree_eval.h"

namespace wavebake::cli {
namespace {

struct EvalFlags {
  std::string store, env;
  int terms = 256;
  EvalOptions options;  // --rotate, --reference-se
  bool reference = false, json = false, no_dense = false;
  int reference_batches = 8;
  driver::AreaLightCommand area;
  GlossyFlags glossy;
  std::vector<std::string> tree_cut_offs;  // SETTING[@LEVEL_WEIGHT] each
  std::string tree_bits = "auto";
};

// --tree-cut-off SETTING[@W]: SETTING "default" (the export's), a cut-off
// C or tE (a target error E); W the level weight (default: the export's).
std::vector<WaveletTreeOptions> TreeSettings(const EvalFlags& f) {
  std::vector<WaveletTreeOptions> out;
  for (const std::string& spec : f.tree_cut_offs) {
    WaveletTreeOptions o;
    absl::StatusOr<std::vector<int>> bits = ParseCodeBits(f.tree_bits);
    if (!bits.ok()) Fail("eval", "--tree-" + std::string(bits.status().message()), kExitBadInput);
    o.bits = *bits;
    std::string c = spec;
    const size_t at = c.find('@');
    bool ok = true;
    if (at != std::string::npos) {
      ok = absl::SimpleAtod(c.substr(at + 1), &o.level_weight);
      c = c.substr(0, at);
    }
    if (c.size() > 1 && c[0] == 't')
      ok = ok && absl::SimpleAtod(c.substr(1), &o.target_error) && o.target_error >= 0;
    else if (c != "default")
      ok = ok && absl::SimpleAtod(c, &o.cut_off) && o.cut_off >= 0;
    if (!ok)
      Fail("eval",
           "--tree-cut-off: '" + spec + "' is not default, a cut-off or tE, then optionally @W",
           kExitBadInput);
    out.push_back(o);
  }
  return out;
}

// The reference's progress on stderr (DESIGN.md §5: a bar on a terminal,
// plain lines otherwise), from the tracing threads.
class ReferenceProgress {
 public:
  ReferenceProgress() : tty_(isatty(STDERR_FILENO) != 0), last_(Clock::now()) {}
  ~ReferenceProgress() {
    if (drawn_ && tty_) std::fputc('\n', stderr);
  }
  void Show(int64_t done, int64_t total) {
    std::lock_guard lock(mu_);
    const auto now = Clock::now();
    const auto every = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(3000);
    if (done != total && now - last_ < every) return;
    last_ = now;
    const double frac = total > 0 ? double(done) / double(total) : 1;
    std::string bar(30, '.');
    std::fill_n(bar.begin(), static_cast<int>(frac * 30), '#');
    // Two visits per sample: the pilot pass, then tracing to the target error.
    std::fprintf(stderr, "%sreference          [%s] %3d%% %s pass%s", tty_ ? "\r" : "", bar.c_str(),
                 static_cast<int>(frac * 100), 2 * done <= total ? "pilot" : "convergence",
                 tty_ ? "\033[K" : "\n");
    std::fflush(stderr);
    drawn_ = true;
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::mutex mu_;
  bool tty_, drawn_ = false;
  Clock::time_point last_;
};

void Run(EvalFlags f) {
  if (!f.area.lights.empty()) {
    f.area.store = f.store;
    absl::StatusOr<std::string> text =
        driver::EvaluateWithAreaLights(f.area, f.reference_batches, f.json);
    if (!text.ok()) Fail("eval", text.status());
    return (void)std::printf("%s\n", text->c_str());
  }
  if (f.env.empty()) Fail("eval", "--env or --area-light is required", kExitBadInput);
  EvalOptions options = f.options;
  options.dense = !f.no_dense;
  ReferenceProgress progress;
  options.reference.progress = [&progress](int64_t done, int64_t total) {
    progress.Show(done, total);
  };
  options.glossy = GlossyOf(f.glossy, "eval");
  if (!f.tree_cut_offs.empty()) {
    absl::StatusOr<driver::TreeEvalReport> trees =
        driver::EvaluateTrees(f.store, f.env, f.terms, options, TreeSettings(f));
    if (!trees.ok()) Fail("eval", trees.status());
    return (void)std::printf("%s", f.json ? (driver::TreeEvalJson(*trees).dump() + "\n").c_str()
                                          : driver::TreeEvalText(*trees).c_str());
  }
  absl::StatusOr<EvalReport> report = driver::Evaluate(f.store, f.env, f.terms, options);
  if (!report.ok()) Fail("eval", report.status());
  std::printf("%s", f.json ? (EvalReportJson(*report).dump() + "\n").c_str()
                           : EvalReportText(*report).c_str());
}

}  // namespace

void AddEvalCommand(CLI::App& app) {
  auto flags = std::make_shared<EvalFlags>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "error of a store's relighting against an independently traced reference");
  cmd->add_option("store", flags->store, "the store (OUT.wbk)")->required();
  cmd->add_option("--env", flags->env, "environment (as for relight)");
  AddAreaLightFlags(*cmd, flags->area);  // the reference: Monte-Carlo over their area
  cmd->add_option("--reference-out", flags->area.reference_out,
                  "area lights: also write the reference image (.png, .exr, .ply)");
  cmd->add_option("--exposure", flags->area.exposure, "--reference-out PNG/PLY exposure, stops");
  cmd->add_flag("--coupling-table", flags->area.table,
                "area lights: look the coupling coefficients up (memory-based) instead");
  cmd->add_option("--reference-batches", flags->reference_batches,
                  "area lights: batches of 16x16 points per light and sample")
      ->capture_default_str();
  // Accepted for the scripts that give it; eval traces the reference always.
  cmd->add_flag("--reference", flags->reference,
                "the Monte-Carlo reference (importance-sampled environment, Embree) is what "
                "eval measures against; it is always traced, this flag only says so");
  cmd->add_option("--terms", flags->terms, "wavelet lights for the compressed relighting")
      ->capture_default_str();
  cmd->add_option("--rotate", flags->options.rotate_degrees,
                  "rotate the environment about +Y, degrees")
      ->capture_default_str();
  cmd->add_option("--reference-se", flags->options.reference.target_rel_se,
                  "target relative standard error of the reference")
      ->capture_default_str();
  cmd->add_option("--bounces", flags->options.bounces,
                  "diffuse bounces of the reference, 0..8 (default: the store's; above 0 a "
                  "path-traced reference with next-event estimation)");
  AddGlossyFlags(*cmd, flags->glossy);
  cmd->add_flag("--no-dense", flags->no_dense,
                "skip retracing the uncompressed rows (T, or V for a visibility store)");
  cmd->add_flag("--json", flags->json,
                "print {\"terms\", \"dense\": {rel_rms, max_abs, psnr, seconds}, "
                "\"compressed\": {...}, \"reference\": {...}}");
  cmd->add_option("--tree-cut-off", flags->tree_cut_offs,
                  "also relight the store's wavelet-tree export at each setting given, "
                  "against the same reference (no dense retrace): 'default' (the export's), "
                  "a cut-off C or tE (a target error E), each optionally @W (level weight)");
  cmd->add_option("--tree-bits", flags->tree_bits,
                  "code bits of the --tree-cut-off exports: auto, B (every level) or one per "
                  "level, level 0 first (as export --bits)")
      ->capture_default_str();
  cmd->callback([flags] { Run(*flags); });
}

}  // namespace wavebake::cli
