// `wavebake cancel JOB --coordinator ADDR` (DESIGN.md §4 Cancel): workers stop
// the job's tasks, and its partial store is removed.
#include <cstdio>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/job_query.h"

namespace wavebake::cli {
namespace {

struct CancelFlags {
  std::string job;
  driver::ClientConfig client;
};

void Run(const CancelFlags& f) {
  absl::StatusOr<driver::Client> client = driver::Client::Connect(f.client);
  if (!client.ok()) Fail("cancel", client.status());
  absl::StatusOr<v1::Job> job = driver::CancelJob(*client, f.job);
  if (!job.ok()) Fail("cancel", job.status());
  std::printf("%s\n", driver::JobOutcome(*job).c_str());
}

}  // namespace

void AddCancelCommand(CLI::App& app) {
  auto f = std::make_shared<CancelFlags>();
  CLI::App* cmd = app.add_subcommand("cancel", "cancel a queued or running job");
  cmd->add_option("JOB", f->job, "job id")->required();
  AddClientFlags(*cmd, f->client);
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
