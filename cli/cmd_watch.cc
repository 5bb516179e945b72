// `wavebake watch JOB --coordinator ADDR` (DESIGN.md §4 Watch): the job's
// progress until it ends — a bar with rays/s and ETA on a terminal, plain
// lines otherwise. Exit 0 if the job is DONE.
#include <cstdio>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "driver/job_query.h"

namespace wavebake::cli {
namespace {

struct WatchFlags {
  std::string job;
  driver::ClientConfig client;
  double patience_seconds = 60;
};

void Run(const WatchFlags& f) {
  absl::StatusOr<driver::Client> client = driver::Client::Connect(f.client);
  if (!client.ok()) Fail("watch", client.status());
  const v1::Job job = FollowJob(*client, f.job, "watch", f.patience_seconds);
  std::printf("%s\n", driver::JobOutcome(job).c_str());
}

}  // namespace

void AddWatchCommand(CLI::App& app) {
  auto f = std::make_shared<WatchFlags>();
  CLI::App* cmd =
      app.add_subcommand("watch", "follow a job's progress until it ends (exit 0 if it is DONE)");
  cmd->add_option("JOB", f->job, "job id")->required();
  AddClientFlags(*cmd, f->client);
  cmd->add_option("--patience", f->patience_seconds,
                  "seconds to keep reconnecting to an unreachable coordinator")
      ->capture_default_str();
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
