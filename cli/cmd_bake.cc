// `wavebake bake SCENE --out OUT.wbk [--workers N] [bake flags]` (DESIGN.md
// §5): the embedded default, a coordinator and N workers in this process
// (cli/embedded_bake.h). SIGINT or SIGTERM cancels the bake; nothing is left
// at OUT. With --auto (cli/auto_bake.h) the light resolution, column
// target and bits are searched for the smallest store within --target-error
// of the independent reference under --env.
#include <atomic>
#include <chrono>
#include <cstdio>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "cli/auto_bake.h"
#include "cli/bake_flags.h"
#include "cli/cluster_commands.h"
#include "cli/command_error.h"
#include "cli/embedded_bake.h"
#include "cli/job_watch.h"
#include "cli/signal_watcher.h"
#include "cli/stderr_log.h"
#include "worker/publish_store.h"

namespace wavebake::cli {
namespace {

struct BakeCommandFlags {
  std::string scene;
  std::string out;
  int workers = 0;
  bool quiet = false;
  BakeFlags bake;
  bool auto_mode = false;
  std::string env = kDefaultAutoEnv;
  int max_light_res = 128;
};

// --auto owns the light resolution, the column terms, the bits and the depth
// mode; it judges by an explicit --target-error. Errors name the flag.
absl::Status CheckAutoFlags(const CLI::App& cmd, const BakeCommandFlags& f) {
  auto given = [&](const char* flag) { return cmd.count(flag) > 0; };
  auto bad = [](const char* flag, const char* why) {
    return absl::InvalidArgumentError(absl::StrCat(flag, ": ", why));
  };
  if (!f.auto_mode) {
    for (const char* flag : {"--env", "--max-light-res"})
      if (given(flag)) return bad(flag, "only with --auto");
    return absl::OkStatus();
  }
  if (!given("--target-error"))
    return bad("--target-error", "--auto needs the relighting error to meet, e.g. 0.05");
  if (given("--light-res")) return bad("--light-res", "--auto chooses the light resolution");
  if (given("--column-terms")) return bad("--column-terms", "--auto selects by --target-error");
  if (f.bake.bits != "auto") return bad("--bits", "--auto needs --bits auto");
  if (f.bake.column_mode != "adaptive")
    return bad("--column-mode", "--auto needs the adaptive column mode");
  const int n = f.max_light_res;
  if (n < 8 || n > 256 || (n & (n - 1)) != 0)
    return bad("--max-light-res", "not a power of two in 8..256");
  return absl::OkStatus();
}

void RunAuto(const BakeCommandFlags& f, const BakeParams& params,
             const std::atomic<bool>& interrupted) {
  AutoBakeOptions options;
  options.env = f.env;
  options.search.target_error = f.bake.target_error;
  options.search.resolutions.clear();
  for (int n = 8; n <= f.max_light_res; n *= 2) options.search.resolutions.push_back(n);
  options.workers = f.workers;
  options.quiet = f.quiet;
  options.interrupted = &interrupted;
  absl::StatusOr<AutoBakeReport> report = AutoBake(f.scene, params, f.out, options);
  if (!report.ok() && absl::IsCancelled(report.status()))
    Fail("bake", "interrupted; nothing written", kExitInterrupted);
  if (!report.ok()) Fail("bake", report.status());
  std::printf("%s", AutoBakeTable(*report).c_str());
  if (!report->failure.empty()) Fail("bake", absl::StrCat("--auto: ", report->failure));
  std::printf("%s: written\n", f.out.c_str());
}

void Run(const CLI::App& cmd, BakeCommandFlags f) {
  LogToStderr(spdlog::level::warn);
  // A link at --out is where the user keeps the store: bake at its target.
  absl::StatusOr<std::filesystem::path> out = ResolveOutputPath(f.out);
  if (!out.ok()) Fail("bake", out.status());
  const std::string given = f.out;
  f.out = out->string();
  std::atomic<bool> interrupted{false};
  SignalWatcher signals([&](int) { interrupted = true; });
  absl::StatusOr<BakeParams> params = ToParams(f.bake);
  if (!params.ok()) Fail("bake", params.status());
  if (absl::Status s = CheckAutoFlags(cmd, f); !s.ok()) Fail("bake", s);
  if (f.auto_mode) return RunAuto(f, *params, interrupted);
  const auto start = std::chrono::steady_clock::now();
  absl::StatusOr<v1::Job> job =
      EmbeddedBake(f.scene, *params, f.out,
                   {.workers = f.workers, .quiet = f.quiet, .interrupted = &interrupted});
  if (!job.ok()) Fail("bake", job.status());
  if (job->phase() == v1::PHASE_CANCELLED && interrupted)
    Fail("bake", "interrupted; nothing written", kExitInterrupted);
  if (job->phase() != v1::PHASE_DONE) Fail("bake", JobOutcome(*job));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s: %d tiles, %d groups, %lld rays, %.2f s\n", given.c_str(), job->tiles(),
              job->groups(), static_cast<long long>(job->rays_traced()), seconds);
  if (!job->stats_json().empty()) std::printf("stats: %s\n", job->stats_json().c_str());
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
  cmd->add_flag("--auto", f->auto_mode,
                "choose the light resolution, column target and bits: the smallest store whose "
                "relighting under --env is within --target-error (relative RMS) of the "
                "independent reference");
  cmd->add_option("--env", f->env,
                  "--auto: the lighting to judge by (EXR/HDR or builtin:NAME); the default's "
                  "small bright sun is the conservative case")
      ->capture_default_str();
  cmd->add_option("--max-light-res", f->max_light_res, "--auto: the finest light resolution to try")
      ->capture_default_str();
  cmd->callback([f, cmd] { Run(*cmd, *f); });
}

}  // namespace wavebake::cli
