// The one-shot clients of a running coordinator (DESIGN.md §4):
// `wavebake watch JOB` follows the job's progress until it ends (a bar with
// rays/s and ETA on a terminal, plain lines otherwise; exit 0 if DONE);
// `cancel JOB` stops its tasks and removes its partial store; `fetch JOB
// --out DIR` copies a finished store without the coordinator's filesystem,
// every array verified before it appears at DIR; `health` exits 0 if the
// coordinator answers SERVING within --timeout (deploy/k8s's probe; no
// token needed).
#include <cstdio>

#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "driver/jobs/health.h"
#include "driver/jobs/job_query.h"
#include "driver/jobs/store_fetch.h"

namespace wavebake::cli {
namespace {

struct WatchFlags {
  std::string job;
  driver::ClientConfig client;
  double patience_seconds = 60;
};

void Run(const WatchFlags& f) {
  const driver::Client client = ConnectOrFail(f.client, "watch");
  const v1::Job job = FollowJob(client, f.job, "watch", f.patience_seconds);
  std::printf("%s\n", driver::JobOutcome(job).c_str());
}

struct CancelFlags {
  std::string job;
  driver::ClientConfig client;
};

void Run(const CancelFlags& f) {
  absl::StatusOr<v1::Job> job = driver::CancelJob(ConnectOrFail(f.client, "cancel"), f.job);
  if (!job.ok()) Fail("cancel", job.status());
  std::printf("%s\n", driver::JobOutcome(*job).c_str());
}

struct FetchFlags {
  std::string job;
  std::string out;
  driver::ClientConfig client;
};

void Run(const FetchFlags& f) {
  const driver::Client client = ConnectOrFail(f.client, "fetch");
  absl::StatusOr<driver::FetchSummary> summary = driver::FetchStore(client, f.job, f.out);
  if (!summary.ok()) Fail("fetch", summary.status());
  std::printf("%s: %d files, %lld bytes, %d arrays verified\n", f.out.c_str(), summary->files,
              static_cast<long long>(summary->bytes), summary->arrays);
}

struct HealthFlags {
  driver::ClientConfig client;
  std::string service;
  double timeout_seconds = 5;
};

void Run(const HealthFlags& f) {
  const driver::Client client = ConnectOrFail(f.client, "health", 0);
  const absl::Status s = driver::CheckHealth(client, f.client.coordinator, f.service,
                                             static_cast<int64_t>(f.timeout_seconds * 1000));
  if (!s.ok()) Fail("health", s);
  std::printf("SERVING\n");
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

void AddCancelCommand(CLI::App& app) {
  auto f = std::make_shared<CancelFlags>();
  CLI::App* cmd = app.add_subcommand("cancel", "cancel a queued or running job");
  cmd->add_option("JOB", f->job, "job id")->required();
  AddClientFlags(*cmd, f->client);
  cmd->callback([f] { Run(*f); });
}

void AddFetchCommand(CLI::App& app) {
  auto f = std::make_shared<FetchFlags>();
  CLI::App* cmd = app.add_subcommand(
      "fetch", "copy a finished job's store from the coordinator to a local directory, verified");
  cmd->add_option("JOB", f->job, "job id")->required();
  cmd->add_option("--out", f->out, "directory to create (must not exist)")->required();
  AddClientFlags(*cmd, f->client);
  cmd->callback([f] { Run(*f); });
}

void AddHealthCommand(CLI::App& app) {
  auto f = std::make_shared<HealthFlags>();
  CLI::App* cmd = app.add_subcommand(
      "health", "check a coordinator's gRPC health (exit 0 if SERVING; a probe for deploy/k8s)");
  AddClientFlags(*cmd, f->client);
  cmd->add_option("--service", f->service, "health service name (default: the whole server)");
  cmd->add_option("--timeout", f->timeout_seconds, "seconds to wait for the answer")
      ->capture_default_str();
  cmd->callback([f] { Run(*f); });
}

}  // namespace wavebake::cli
