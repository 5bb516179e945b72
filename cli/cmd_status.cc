// `wavebake status [JOB] --coordinator ADDR` (DESIGN.md §4 Get, List): one
// job in detail, or the newest jobs as a table; --json prints the Job
// messages as JSON (one per line) for scripts.
#include <google/protobuf/util/json_util.h>

#include <cstdio>

#include "absl/strings/str_cat.h"
#include "cli/client_flags.h"
#include "cli/command_error.h"
#include "cli/commands.h"
#include "cli/stderr_log.h"
#include "driver/job_query.h"

namespace wavebake::cli {
namespace {

struct StatusFlags {
  std::string job;
  driver::ClientConfig client;
  bool json = false;
  bool active = false;
  int limit = 20;
};

std::string Phase(const v1::Job& job) { return v1::Phase_Name(job.phase()).substr(6); }

void PrintJson(const v1::Job& job) {
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  (void)google::protobuf::util::MessageToJsonString(job, &json, options);
  std::printf("%s\n", json.c_str());
}

void PrintDetail(const v1::Job& job) {
  std::printf("job        %s\n", job.id().c_str());
  std::printf("phase      %s\n", Phase(job).c_str());
  std::printf("store      %s\n", job.store_path().c_str());
  std::printf("tasks      %d/%d done (%d tiles, %d groups, 1 finalize), %d leased\n",
              job.tasks_done(), job.tasks_total(), job.tiles(), job.groups(), job.leased_tasks());
  std::printf("rays       %lld of ~%lld", static_cast<long long>(job.rays_traced()),
              static_cast<long long>(job.rays_estimate()));
  if (job.rays_per_second() > 0) std::printf(", %.2f Mrays/s", job.rays_per_second() / 1e6);
  if (job.eta_seconds() >= 0) std::printf(", ETA %.0f s", job.eta_seconds());
  std::printf("\nwritten    %lld bytes\n", static_cast<long long>(job.bytes_written()));
  if (!job.error().empty()) std::printf("error      %s\n", job.error().c_str());
  if (!job.stats_json().empty()) std::printf("stats      %s\n", job.stats_json().c_str());
}

void PrintRow(const v1::Job& job) {
  std::printf("%-6s %-13s %9s %12.4g %-24s %s\n", job.id().c_str(), Phase(job).c_str(),
              absl::StrCat(job.tasks_done(), "/", job.tasks_total()).c_str(),
              static_cast<double>(job.rays_traced()), job.store_path().c_str(),
              job.error().c_str());
}

void Run(const StatusFlags& f) {
  LogToStderr(spdlog::level::warn);
  absl::StatusOr<driver::Client> client = driver::Client::Connect(f.client);
  if (!client.ok()) Fail("status", client.status());
  if (!f.job.empty()) {
    absl::StatusOr<v1::Job> job = driver::GetJob(*client, f.job);
    if (!job.ok()) Fail("status", job.status());
    f.json ? PrintJson(*job) : PrintDetail(*job);
    return;
  }
  absl::StatusOr<std::vector<v1::Job>> jobs = driver::ListJobs(*client, f.limit, f.active);
  if (!jobs.ok()) Fail("status", jobs.status());
  if (!f.json)
    std::printf("%-6s %-13s %9s %12s %-24s %s\n", "JOB", "PHASE", "TASKS", "RAYS", "STORE",
                "ERROR");
  for (const v1::Job& job : *jobs) f.json ? PrintJson(job) : PrintRow(job);
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
