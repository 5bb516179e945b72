// `wavebake cancel JOB --coordinator ADDR` (DESIGN.md §4 Cancel): workers stop
// the job's tasks, and its partial store is removed.
#include <cstdio>

#include "cli/client.h"
#include "cli/cluster_commands.h"
#include "cli/command_error.h"
#include "cli/job_watch.h"
#include "cli/stderr_log.h"

namespace wavebake::cli {
namespace {

struct CancelFlags {
  std::string job;
  ClientFlags client;
};

void Run(const CancelFlags& f) {
  LogToStderr(spdlog::level::warn);
  absl::StatusOr<Client> client = Client::Connect(f.client);
  if (!client.ok()) Fail("cancel", client.status());
  v1::JobId id;
  id.set_id(f.job);
  v1::Job job;
  if (grpc::Status s = client->jobs().Cancel(client->Call().get(), id, &job); !s.ok())
    Fail("cancel", FromGrpc(s));
  std::printf("%s\n", JobOutcome(job).c_str());
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
