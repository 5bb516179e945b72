// `wavebake status [JOB] --coordinator ADDR` (DESIGN.md §4 Get, List): one
// job in detail, or the newest jobs as a table; --json prints the Job
// messages as JSON (one per line) for scripts.
#include <cstdio>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/job_text.h"

namespace wavebake::cli {
namespace {

struct StatusFlags {
  std::string job;
  driver::ClientConfig client;
  bool json = false;
  bool active = false;
  int limit = 20;
};

void Run(const StatusFlags& f) {
  const driver::Client client = ConnectOrFail(f.client, "status");
  if (!f.job.empty()) {
    absl::StatusOr<v1::Job> job = driver::GetJob(client, f.job);
    if (!job.ok()) Fail("status", job.status());
    std::printf("%s", (f.json ? driver::JobJson(*job) : driver::JobDetailText(*job)).c_str());
    return;
  }
  absl::StatusOr<std::vector<v1::Job>> jobs = driver::ListJobs(client, f.limit, f.active);
  if (!jobs.ok()) Fail("status", jobs.status());
  if (!f.json) std::printf("%s", driver::JobTableHeader().c_str());
  for (const v1::Job& job : *jobs)
    std::printf("%s", (f.json ? driver::JobJson(job) : driver::JobTableRow(job)).c_str());
}

}  // namespace

void AddStatusCommand(CLI::App& app) {
  auto f = std::make_shared<StatusFlags>();
  CLI::App* cmd = app.add_subcommand("status", "show one job, or the newest jobs of a coordinator");
  cmd->add_option("JOB", f->job, "job id (default: list jobs)");
  AddClientFlags(*cmd, f->client);
  cmd->add_flag("--json", f->json, "print the jobs as JSON, one per line");
  cmd->add_flag("--active", f->active, "list only jobs that have not ended");
  cmd->add_option("--limit", f->limit, "list at most this many jobs, newest first")
      ->capture_default_str();
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
