// `wavebake bake SCENE --out OUT.wbk [--workers N] [bake flags]` (DESIGN.md
// §5): the embedded default, a coordinator and N workers in this process
// (cli/embedded_bake.h). SIGINT or SIGTERM cancels the bake; nothing is left
// at OUT.
#include <atomic>
#include <chrono>
#include <cstdio>

#include "cli/bake_flags.h"
#include "cli/cluster_commands.h"
#include "cli/command_error.h"
#include "cli/embedded_bake.h"
#include "cli/job_watch.h"
#include "cli/signal_watcher.h"
#include "cli/stderr_log.h"

namespace wavebake::cli {
namespace {

struct BakeCommandFlags {
  std::string scene;
  std::string out;
  int workers = 0;
  bool quiet = false;
  BakeFlags bake;
};

void Run(const BakeCommandFlags& f) {
  LogToStderr(spdlog::level::warn);
  std::atomic<bool> interrupted{false};
  SignalWatcher signals([&](int) { interrupted = true; });
  absl::StatusOr<BakeParams> params = ToParams(f.bake);
  if (!params.ok()) Fail("bake", params.status());
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
  std::printf("%s: %d tiles, %d groups, %lld rays, %.2f s\n", f.out.c_str(), job->tiles(),
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
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
