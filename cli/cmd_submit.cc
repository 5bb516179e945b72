// `wavebake submit SCENE [bake flags] [--update JOB [--update-exact]]
// --coordinator ADDR [--wait]` (DESIGN.md §4, §5): prints the new job's id
// on stdout; with --wait, follows the job like `watch` and exits 0 only if
// it is DONE.
#include <cstdio>

#include "cli/bake_flags.h"
#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/job_submit.h"

namespace wavebake::cli {
namespace {

struct SubmitFlags {
  std::string scene;
  BakeFlags bake;
  driver::ClientConfig client;
  std::string output_name;
  int max_attempts = kDefaultMaxAttempts;
  bool wait = false;
};

void Run(const SubmitFlags& f) {
  absl::StatusOr<BakeParams> params = ParseBakeParamWords(f.bake.params, f.bake.words);
  if (!params.ok()) Fail("submit", params.status());
  const driver::Client client = ConnectOrFail(f.client, "submit");
  absl::StatusOr<v1::Job> job =
      driver::SubmitBake(client, *params, f.output_name, f.max_attempts, f.scene);
  if (!job.ok()) Fail("submit", job.status());
  std::printf("%s\n", job->id().c_str());
  std::fflush(stdout);
  if (!f.wait) return;
  const v1::Job ended = FollowJob(client, job->id(), "submit");
  std::fprintf(stderr, "%s\n", driver::JobOutcome(ended).c_str());
}

}  // namespace

void AddSubmitCommand(CLI::App& app) {
  auto f = std::make_shared<SubmitFlags>();
  CLI::App* cmd = app.add_subcommand(
      "submit", "submit a bake job to a coordinator; prints its id (uploads a scene file once)");
  cmd->add_option("SCENE", f->scene, "builtin:NAME, a mesh file (OBJ, PLY, glTF) or a .json scene")
      ->required();
  AddBakeFlags(*cmd, f->bake);
  AddClientFlags(*cmd, f->client);
  cmd->add_option("--output-name", f->output_name,
                  "store directory under the store root (default job-<id>.wbk)");
  cmd->add_option("--max-attempts", f->max_attempts,
                  "failures and lease expiries a task may take before the job fails")
      ->capture_default_str();
  CLI::Option* update = cmd->add_option(
      "--update", f->bake.params.update_job,
      "a DONE job of this coordinator (its id or output name), baked with --keep-staging and "
      "the same flags: reuse its rows where the scene's edit cannot reach them");
  cmd->add_flag("--update-exact", f->bake.params.update_exact,
                "--update: rerun the whole column stage from the merged rows (the store is "
                "byte-identical to a full bake but for .zattrs' \"update\" record)")
      ->needs(update);
  cmd->add_flag("--wait", f->wait, "follow the job to its end (exit 0 only if DONE)");
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
