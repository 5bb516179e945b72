// `wavebake bake SCENE --out OUT.wbk [--workers N] [bake flags]` (DESIGN.md
// §5): the embedded default, a coordinator and N workers in this process
// (driver/bake/embedded_bake.h). SIGINT or SIGTERM cancels the bake; nothing is left
// at OUT. With --auto (driver/bake/auto_bake.h) the light resolution, column
// target and bits are searched for the smallest store within --target-error
// of the independent reference under --env. With --serve the web monitor
// follows the bake and then relights its store (web/bake_monitor.h).
#include <atomic>
#include <chrono>
#include <cstdio>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "cli/bake_flags.h"
#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/web_flags.h"
#include "driver/bake/auto_bake.h"
#include "driver/bake/embedded_bake.h"
#include "driver/bake/update_bake.h"
#include "driver/jobs/job_query.h"
#include "driver/process/signal_watcher.h"
#include "web/bake_monitor.h"

namespace wavebake::cli {
namespace {

struct BakeCommandFlags {
  std::string scene;
  std::string out;
  int workers = 0;
  bool quiet = false;
  BakeFlags bake;
  bool auto_mode = false;
  std::vector<std::string> envs;  // --auto: empty means driver::kDefaultAutoEnv
  int max_light_res = 128;
  WebFlags web;
  std::string token_file;
};

void RunAuto(const BakeCommandFlags& f, const BakeParams& params,
             const std::atomic<bool>& interrupted) {
  ProgressBar display(f.quiet);
  driver::AutoBakeOptions options;
  if (!f.envs.empty()) options.envs = f.envs;
  options.search.target_error = f.bake.params.target_error;
  options.search.resolutions.clear();
  for (int n = 8; n <= f.max_light_res; n *= 2) options.search.resolutions.push_back(n);
  options.workers = f.workers;
  if (!f.quiet) {
    options.on_message = [&](const std::string& line) {
      display.Finish();
      std::fprintf(stderr, "auto: %s\n", line.c_str());
    };
  }
  options.interrupted = &interrupted;
  absl::StatusOr<driver::AutoBakeReport> report = driver::AutoBake(f.scene, params, f.out, options);
  display.Finish();
  if (!report.ok() && absl::IsCancelled(report.status()))
    Fail("bake", "interrupted; nothing written", kExitInterrupted);
  if (!report.ok()) Fail("bake", report.status());
  std::printf("%s", driver::AutoBakeTable(*report).c_str());
  if (!report->failure.empty()) Fail("bake", absl::StrCat("--auto: ", report->failure));
  std::printf("%s: written\n", f.out.c_str());
}

void Run(BakeCommandFlags f) {
  // A link at --out is where the user keeps the store: bake at its target.
  absl::StatusOr<std::filesystem::path> out = ResolveOutputPath(f.out);
  if (!out.ok()) Fail("bake", out.status());
  const std::string given = f.out;
  f.out = out->string();
  std::atomic<bool> interrupted{false};
  driver::SignalWatcher signals([&](int) { interrupted = true; });
  absl::StatusOr<BakeParams> params = ParseBakeParamWords(f.bake.params, f.bake.words);
  if (!params.ok()) Fail("bake", params.status());
  if (f.auto_mode) return RunAuto(f, *params, interrupted);
  const auto start = std::chrono::steady_clock::now();
  WebFlags web = f.web;
  web.options.token = TokenOrFail(f.token_file, "bake");
  web::BakeMonitor monitor(StartMonitor("bake", std::move(web), nullptr), f.out);
  ProgressBar display(f.quiet);
  driver::EmbeddedBakeOptions options{
      .workers = f.workers, .on_event = display.Callback(), .interrupted = &interrupted};
  monitor.Attach(options);
  absl::StatusOr<v1::Job> job = driver::EmbeddedBake(f.scene, *params, f.out, options);
  display.Finish();
  if (!job.ok()) Fail("bake", job.status());
  if (job->phase() == v1::PHASE_CANCELLED && interrupted)
    Fail("bake", "interrupted; nothing written", kExitInterrupted);
  if (job->phase() != v1::PHASE_DONE) Fail("bake", driver::JobOutcome(*job));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %d tiles, %d groups, %lld rays, %.2f s\n", given.c_str(), job->tiles(),
              job->groups(), static_cast<long long>(job->rays_traced()), seconds);
  if (!job->stats_json().empty()) std::printf("stats: %s\n", job->stats_json().c_str());
  if (const std::string update = driver::UpdateSummary(f.out); !update.empty())
    std::printf("%s\n", update.c_str());
  if (monitor) ServeUntil("bake", monitor.server(), interrupted);
}

}  // namespace

void AddBakeCommand(CLI::App& app) {
  auto f = std::make_shared<BakeCommandFlags>();
  CLI::App* cmd = app.add_subcommand(
      "bake", "bake SCENE into a compressed transport store (coordinator and workers in-process)");
  cmd->add_option("SCENE", f->scene, "builtin:NAME, a mesh file (OBJ, PLY, glTF) or a .json scene")
      ->required();
  cmd->add_option("--out", f->out, "the store to write, e.g. scene.wbk (replaced if a store)")
      ->required();
  cmd->add_option("--workers", f->workers, "worker loops, one task each at a time (0: one per CPU)")
      ->capture_default_str();
  cmd->add_flag("--quiet", f->quiet, "no progress on stderr");
  AddBakeFlags(*cmd, f->bake);
  CLI::Option* update =
      cmd->add_option("--update", f->bake.params.update_from,
                      "OLD.wbk, baked with --keep-staging and the same flags: reuse its rows "
                      "where the scene's edit cannot reach them, rebake the others");
  cmd->add_flag("--update-exact", f->bake.params.update_exact,
                "--update: rerun the whole column stage from the merged rows (the store is "
                "byte-identical to a full bake but for .zattrs' \"update\" record)")
      ->needs(update);
  // --auto owns the light resolution and the column terms, and judges by an
  // explicit --target-error (the parser's errors name the flags).
  CLI::Option* auto_flag =
      cmd->add_flag("--auto", f->auto_mode,
                    "choose the light resolution, column target and bits: the smallest store "
                    "whose relighting under every --env is within --target-error (relative RMS) "
                    "of the independent reference")
          ->needs(cmd->get_option("--target-error"))
          ->excludes(cmd->get_option("--light-res"))
          ->excludes(cmd->get_option("--column-terms"));
  cmd->add_option("--env", f->envs,
                  "--auto: a lighting to judge by (EXR/HDR or builtin:NAME); repeat it to judge "
                  "by several, the worst error counting. Default: builtin:sky, whose small "
                  "bright sun is the conservative case")
      ->take_all()
      ->needs(auto_flag);
  cmd->add_option("--max-light-res", f->max_light_res, "--auto: the finest light resolution to try")
      ->needs(auto_flag)
      ->check(CLI::IsMember({8, 16, 32, 64, 128, 256}))
      ->capture_default_str();
  AddWebFlags(*cmd, f->web, "--serve",
              "serve the web monitor on host:port while baking, then the finished store's "
              "relight view until Ctrl-C");
  cmd->add_option("--token-file", f->token_file,
                  "--serve: require this bearer token (first line of the file)")
      ->needs(cmd->get_option("--serve"));
  cmd->get_option("--serve")->excludes(auto_flag);
  update->excludes(auto_flag);
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
